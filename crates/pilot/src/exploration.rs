//! Exploration mode: the pilot runs the mission's state machine each control step,
//! plans and follows the paths it asks for, and works its gripper.

use super::Pilot;
use super::mode::Mode;
use super::navigation::Target;
use navdeck_core::data::Level;
use navdeck_core::geometry::Twist;
use navdeck_core::mission::machine::Mission;
use navdeck_core::mission::step::{Inputs, Motion, PathStatus};
use std::collections::BTreeMap;

/// How far the console may move a mission goal that lies in an obstacle, metres.
const GOAL_TOLERANCE: f64 = 0.3;

/// What exploration mode keeps between steps.
#[derive(Debug, Default)]
pub(super) struct Exploring {
    pub mission: Option<Mission>,
    /// IDs of the newest camera frame not yet shown to the mission, if one arrived.
    pub frame: Option<Vec<u32>>,
    /// The last mission step: when, and the twist it gave.
    pub last_step: Option<(f64, Twist)>,
    /// Why the last plan the mission asked for failed.
    pub no_path: Option<String>,
    /// Session time the mission started.
    pub started: f64,
    /// The times the mission was held (e-stop, a lost sensor), which its clock does not
    /// count (a hold is no lack of progress): its clock's reading as each began, and how
    /// long it lasted; and since when (session time) it is held now.
    pub holds: Vec<(f64, f64)>,
    pub held_since: Option<f64>,
}

impl Pilot {
    /// On entering exploration mode: the mission kept since a takeover resumes, else one
    /// starts.
    pub(super) fn enter_mission(&mut self) {
        let (now, gripper) = (self.mission_clock(self.now), self.hand.state);
        let Some(mission) = self.exploring.mission.as_mut() else {
            return self.start_mission();
        };
        let resumed = mission.resume(now, gripper);
        self.drop_route();
        self.exploring.last_step = None;
        self.exploring.no_path = None;
        for id in &resumed.forget {
            self.ekf.forget(*id);
            self.estimating.ignored_markers.retain(|m| m != id);
        }
        self.belief.drop_landmarks(&resumed.forget);
        for (level, text) in resumed.log {
            self.log(level, text);
        }
    }

    /// Starts a fresh mission.
    pub(super) fn start_mission(&mut self) {
        self.drop_route();
        let mission = Mission::new(self.settings.mission.clone(), self.mission_clock(self.now));
        // With an arm, the mission picks with it (seed 000) instead of driving into blocks.
        let mission = match &self.settings.arm {
            Some(arm) => mission.with_arm(arm.clone()),
            None => mission,
        };
        self.exploring.mission = Some(mission);
        self.exploring.last_step = None;
        self.exploring.no_path = None;
        self.exploring.started = self.now;
        self.log(Level::Info, "exploration: the mission starts");
    }

    /// The camera frame's marker IDs, kept for the mission's next step.
    pub(super) fn note_frame(&mut self, ids: Vec<u32>) {
        self.exploring.frame = Some(ids);
    }

    /// One mission step at `t`; between control ticks the last command stands.
    pub(super) fn explore(&mut self, t: f64) -> Twist {
        if let Err(twist) = self.step_due(self.exploring.last_step, t) {
            return twist;
        }
        let Some(mut mission) = self.exploring.mission.take() else {
            return Twist::ZERO;
        };
        let landmarks: BTreeMap<_, _> = self.ekf.landmarks().map(|l| (l.id, l.mean)).collect();
        let frame = self.exploring.frame.take();
        let path = self.path_status();
        let scan = self.scan_here();
        let outputs = mission.step(&Inputs {
            t: self.mission_clock(t),
            pose: self.pose(),
            landmarks: &landmarks,
            seen: frame.as_deref().unwrap_or(&[]),
            camera_frame: frame.is_some(),
            gripper: self.hand.state,
            path: &path,
            map: self.belief.costmap(),
            occupied: self.belief.sensed_occupied(),
            scan: &scan,
            position_std: self.position_std(),
            // The lidar places the robot without markers: MCL once it converged, lidar SLAM
            // always.
            localized: self.mcl().is_some_and(|m| m.status().converged)
                || self.lidar_slam().is_some(),
            arm: self.hand.arm.as_ref().and_then(|a| a.measured).map(|j| j.0),
            can_pick: !self.sensor_lost(navdeck_core::health::Sensor::Arm),
        });
        self.exploring.mission = Some(mission);
        for (level, text) in outputs.log {
            self.log_at(t, level, text);
        }
        self.estimating.ignored_markers = outputs.ignore_markers;
        if let Some(cmd) = outputs.gripper {
            self.hand.pending = Some(cmd);
        }
        if let (Some(joints), Some(arm)) = (outputs.arm, self.hand.arm.as_mut()) {
            arm.move_to(navdeck_core::arm::Joints(joints));
        }
        if outputs.to_manual {
            self.log(Level::Warn, "mission handed the robot to manual control");
            self.set_mode(Mode::Manual);
            return Twist::ZERO;
        }
        if matches!(outputs.motion, Motion::Stop | Motion::Drive(_)) && self.nav.arrived {
            // The mission has moved on from the goal it reached: its route is done.
            self.drop_route();
            self.nav.arrived = false;
        }
        let twist = match outputs.motion {
            Motion::Stop => {
                self.follower.clear_trajectory();
                Twist::ZERO
            }
            Motion::Drive(twist) => {
                self.follower.clear_trajectory();
                self.guarded_drive(twist)
            }
            Motion::PlanTo { goal, label } => {
                self.nav.last_step = None;
                // A goal that the map has since filled in moves to the nearest open spot.
                let goal = navdeck_core::map::reach::nearest_passable(
                    self.belief.costmap(),
                    goal,
                    GOAL_TOLERANCE,
                )
                .unwrap_or(goal);
                if self.plan_route(Target::Point(goal)) {
                    self.exploring.no_path = None;
                    if let Some(route) = self.nav.route.as_mut() {
                        route.label = label;
                        self.follower.set_trajectory(route.plan.trajectory.clone());
                    }
                    self.nav.arrived = false;
                    self.follow(t)
                } else {
                    self.exploring.no_path = Some(format!("no path to {label}"));
                    Twist::ZERO
                }
            }
            Motion::Follow => self.follow(t),
        };
        self.exploring.last_step = Some((t, twist));
        twist
    }

    /// The mission's clock at session time `t`: the session's, less the time it was held.
    fn mission_clock(&self, t: f64) -> f64 {
        let holding = self.exploring.held_since.map_or(0.0, |since| t - since);
        let held: f64 = self.exploring.holds.iter().map(|h| h.1).sum();
        t - held - holding
    }

    /// The session time at which the mission's clock read `m` (its timeline's times).
    pub fn session_time_of(&self, m: f64) -> f64 {
        let before = self.exploring.holds.iter().filter(|h| h.0 < m);
        m + before.map(|h| h.1).sum::<f64>()
    }

    /// Whether the task was held at `t` (suppressed by the e-stop or sensor health): the
    /// mission's clock stands still meanwhile.
    pub(super) fn note_task_held(&mut self, t: f64, held: bool) {
        match (held, self.exploring.held_since) {
            (true, None) => self.exploring.held_since = Some(t),
            (false, Some(since)) => {
                let began = self.mission_clock(since);
                self.exploring.holds.push((began, (t - since).max(0.0)));
                self.exploring.held_since = None;
            }
            _ => {}
        }
    }

    /// How the path the mission asked for is going.
    fn path_status(&self) -> PathStatus {
        if let Some(reason) = &self.exploring.no_path {
            return PathStatus::NoPath(reason.clone());
        }
        if self.follower.trajectory().is_none() {
            return PathStatus::Idle;
        }
        if self.nav.arrived {
            return PathStatus::Arrived;
        }
        PathStatus::Following {
            remaining: self.nav.following.map_or(f64::INFINITY, |f| f.remaining),
        }
    }

    /// Seconds since the mission started.
    pub fn mission_elapsed(&self) -> f64 {
        self.now - self.exploring.started
    }

    /// The running mission, for the status panel and the mission runner.
    pub fn mission(&self) -> Option<&Mission> {
        self.exploring.mission.as_ref()
    }
}
