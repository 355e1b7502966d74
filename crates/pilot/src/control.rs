//! Sense, decide, act: folding in what the robot reported and choosing the command.

use super::Pilot;
use crate::behaviours::camera_usable;
use crate::reckoning::Reckoning;
use navdeck_core::data::{Command, GripperState, Level, SensorFrame, WheelTravel};
use navdeck_core::geometry::Twist;
use navdeck_core::map::contact::JAWS;
use navdeck_core::slam::odometry::twist_from_wheels;

/// The commanded and measured twists, and the wheel travel and time since the measured
/// one was last worked out.
#[derive(Clone, Debug, Default)]
pub(super) struct Measuring {
    /// The twist last commanded, and the one the wheels measured.
    pub commanded: Twist,
    pub measured: Twist,
    travel: WheelTravel,
    travel_time: f64,
    /// The commands sent since the wheels last reported travel, and when: what the robot
    /// was asked to drive while its odometry was silent.
    pub unmeasured: std::collections::VecDeque<(f64, Twist)>,
    /// The motion reckoned from those commands once odometry was found lost, on until
    /// the wheels report again: a link whose first travel then spans the silence reports
    /// it again.
    pub reckoning: Option<Reckoning>,
}

/// Commands remembered while the wheels are silent, at most: a minute at 10 Hz.
const UNMEASURED_KEPT: usize = 600;
/// A travel spans a silence when it covers all but this much of it, seconds.
const SPAN_SLACK_S: f64 = 0.05;

impl Pilot {
    /// Folds in what the robot reported up to `t`.
    pub(super) fn sense(&mut self, t: f64, frame: &SensorFrame) {
        self.link_answered(t);
        self.note_sensor_health(t, frame);
        if let Some(arm) = frame.arm {
            self.arm_measured(arm.joints);
        }
        if let Some(pose) = frame.initial_pose {
            self.set_pose(pose);
        }
        if let Some(goal) = frame.goal {
            self.drive_to_goal(goal);
        }
        if let Some(mut wheels) = frame.wheels {
            self.measuring.unmeasured.clear();
            if let Some(reckoning) = self.measuring.reckoning.take()
                && frame.elapsed >= t - reckoning.since - SPAN_SLACK_S
            {
                // The wheels counted on through the silence (a ROS odometry whose messages
                // were lost): the part reckoned is in this travel already.
                wheels.left -= reckoning.travel.left;
                wheels.right -= reckoning.travel.right;
            }
            self.estimate_motion(wheels);
            self.measuring.travel.left += wheels.left;
            self.measuring.travel.right += wheels.right;
            self.measuring.travel_time += frame.elapsed;
        }
        // A dark or failed frame shows nothing, which is no evidence that nothing is there.
        if let Some(s) = frame.sightings.as_ref().filter(|_| camera_usable(frame)) {
            self.estimate_sightings(s);
            self.map_sightings(s);
            self.note_frame(s.iter().map(|m| m.id).collect());
        }
        if let Some(lane) = &frame.lane {
            self.sense_lane(lane);
        }
        // The tag camera may be a camera of its own (a ROS 2 robot's /rgb): its frames
        // count unless the frame reports a failed camera.
        let camera_failed = frame.camera.as_ref().is_some_and(|c| c.error.is_some());
        if let Some(tags) = frame.tags.as_ref().filter(|_| !camera_failed) {
            self.sense_tags(t, tags);
        }
        if let Some(scan) = &frame.scan {
            self.note_scan_for_monitor(t);
            self.localize_scan(scan);
            self.map_scan(t, scan);
        }
        if let Some(g) = frame.gripper {
            if self.hand.state.is_some() && self.hand.state != Some(g) {
                self.log_at(t, Level::Info, format!("gripper {}", g.label()));
            }
            if g == GripperState::Holding && self.hand.state != Some(g) {
                // What the lidar mapped in the jaws is the block, gone from that spot.
                self.belief.clear_held(self.pose(), JAWS);
            }
            self.hand.state = Some(g);
        }
    }

    /// Decides the command for `t`.
    pub(super) fn act(&mut self, t: f64) -> Command {
        self.sync_keepout();
        let twist = self.decide(t);
        // The zones' speed limit caps whichever behaviour's command won.
        let twist = self.zone_speed_cap(twist);
        self.measuring.commanded = twist;
        self.reckon_on(t, twist);
        let unmeasured = &mut self.measuring.unmeasured;
        if unmeasured.len() == UNMEASURED_KEPT {
            unmeasured.pop_front();
        }
        unmeasured.push_back((t, twist));
        Command {
            twist,
            gripper: self.hand.pending.take(),
            arm: self.arm_command(t),
        }
    }

    /// While odometry is lost, the motion the command in force drove up to `t` goes into
    /// the estimate, and `twist` is the command from now on.
    fn reckon_on(&mut self, t: f64, twist: Twist) {
        let robot = &self.settings.robot;
        let Some(reckoning) = self.measuring.reckoning.as_mut() else {
            return;
        };
        let stretch = reckoning.advance(t, robot);
        reckoning.command(twist);
        if stretch != WheelTravel::default() {
            self.estimate_motion(stretch);
        }
    }

    /// The measured twist over the last control period: whole periods, so that encoder
    /// quantisation does not make it flicker.
    pub(super) fn measure(&mut self) {
        let period = self.settings.robot.control_period;
        let m = &mut self.measuring;
        if m.travel_time >= 0.5 * period {
            m.measured = twist_from_wheels(m.travel, self.settings.robot.track, m.travel_time);
            m.travel = WheelTravel::default();
            m.travel_time = 0.0;
        }
    }

    /// For an autonomous mode's step at `t` after its last one (`last`: when, and the twist
    /// it gave): `Err(twist)` when that step was under half a period ago and its command
    /// stands (decide also runs on key events between ticks), else `Ok(dt)`.
    pub(super) fn step_due(&self, last: Option<(f64, Twist)>, t: f64) -> Result<f64, Twist> {
        let period = self.settings.robot.control_period;
        match last {
            Some((at, twist)) if t - at < 0.5 * period => Err(twist),
            Some((at, _)) => Ok(t - at),
            None => Ok(period),
        }
    }

    /// Seconds the robot needs to brake from the current command at its acceleration limits.
    pub(super) fn brake_margin(&self) -> f64 {
        let r = &self.settings.robot;
        (self.measuring.commanded.linear.abs() / r.max_linear_accel)
            .max(self.measuring.commanded.angular.abs() / r.max_angular_accel)
    }

    /// When the held keys' deadman cuts the drive command, no earlier than `now`: early
    /// enough that the robot, braking at its acceleration limits, is at rest
    /// `deadman_timeout` after the last key.
    pub fn teleop_cutoff(&self, now: f64) -> Option<f64> {
        let expiry = self.teleop.next_expiry(self.brake_margin())?;
        Some(expiry.max(now))
    }
}
