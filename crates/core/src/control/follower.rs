//! The follower: owns the trajectory and the chosen controller, tracks progress, limits the
//! command and says when the robot has arrived.

use super::config::{ControllerKind, FollowConfig};
use super::controller::{Limits, PathController};
use super::hybrid::Hybrid;
use super::pid_follower::PidFollower;
use super::pure_pursuit::PurePursuit;
use super::tracking::{Progress, ProgressTracker};
use crate::geometry::{Pose2, Twist};
use crate::plan::trajectory::Trajectory;

/// What the follower is doing after a step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FollowStatus {
    /// Nothing to follow (seed 004 section D: "no_traj").
    NoTrajectory,
    /// On the way: arc length (m) and planned time (s) left, signed cross-track error (m,
    /// positive when the path lies to the robot's left).
    Following {
        remaining: f64,
        eta: f64,
        cross_track: f64,
    },
    /// At the goal's position, turning in place to its heading: the error left, radians.
    Turning { error: f64 },
    /// Within the goal tolerance (seed 004 section D: "finished"); the twist is zero from now on.
    Arrived,
}

/// One step's command and status.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FollowStep {
    pub twist: Twist,
    pub status: FollowStatus,
}

/// Turn rate per radian of heading error when turning to a goal's heading, 1/s.
const TURN_GAIN: f64 = 2.0;

/// Follows one trajectory at a time with a switchable controller.
#[derive(Debug)]
pub struct Follower {
    config: FollowConfig,
    limits: Limits,
    kind: ControllerKind,
    controller: Box<dyn PathController>,
    trajectory: Option<Trajectory>,
    tracker: ProgressTracker,
    progress: Option<Progress>,
    /// The heading to end with (a goal pose's), radians; None ends facing the path.
    goal_heading: Option<f64>,
    /// At the goal's position; with a goal heading, turning to it until `arrived`.
    at_goal: bool,
    arrived: bool,
    squares: f64,
    samples: usize,
}

impl Follower {
    /// Arrival counts only with less than this arc length left, metres, so a path that
    /// starts where it ends is not finished at its start.
    pub const END_ZONE: f64 = 0.3;

    /// A follower with no trajectory; `max_linear` (m/s) and `max_angular` (rad/s) bound
    /// every command.
    pub fn new(config: FollowConfig, max_linear: f64, max_angular: f64) -> Self {
        let limits = Limits {
            max_linear,
            max_angular,
        };
        let kind = config.controller;
        Self {
            controller: build(kind, &config, limits),
            config,
            limits,
            kind,
            trajectory: None,
            tracker: ProgressTracker::default(),
            progress: None,
            goal_heading: None,
            at_goal: false,
            arrived: false,
            squares: 0.0,
            samples: 0,
        }
    }

    /// The heading to end with once at the goal (RViz's "2D Goal Pose"), or None to stop
    /// facing along the path's end. Kept across trajectories until changed.
    pub fn set_goal_heading(&mut self, heading: Option<f64>) {
        self.goal_heading = heading;
        self.arrived = false;
    }

    /// Starts following `trajectory` from its beginning; an empty one clears it.
    pub fn set_trajectory(&mut self, trajectory: Trajectory) {
        self.trajectory = (!trajectory.is_empty()).then_some(trajectory);
        self.restart();
    }

    /// Stops following; later steps return zero.
    pub fn clear_trajectory(&mut self) {
        self.trajectory = None;
        self.restart();
    }

    pub fn trajectory(&self) -> Option<&Trajectory> {
        self.trajectory.as_ref()
    }

    /// Switches the control law mid-path; the new one starts with fresh state.
    pub fn set_controller(&mut self, kind: ControllerKind) {
        self.kind = kind;
        self.controller = build(kind, &self.config, self.limits);
        self.controller.reset();
    }

    pub fn controller(&self) -> ControllerKind {
        self.kind
    }

    /// The progress measured at the last step.
    pub fn progress(&self) -> Option<&Progress> {
        self.progress.as_ref()
    }

    /// At the goal's position, still turning to its heading.
    pub fn is_turning_to_heading(&self) -> bool {
        self.at_goal && !self.arrived
    }

    /// Root mean square of the cross-track error over the steps of this trajectory, metres.
    pub fn cross_track_rms(&self) -> Option<f64> {
        (self.samples > 0).then(|| (self.squares / self.samples as f64).sqrt())
    }

    /// The command for a robot at `pose`, `dt` seconds after the previous step.
    pub fn step(&mut self, pose: Pose2, dt: f64) -> FollowStep {
        let Some(trajectory) = self.trajectory.as_ref() else {
            return stopped(FollowStatus::NoTrajectory);
        };
        if self.arrived {
            return stopped(FollowStatus::Arrived);
        }
        if self.at_goal {
            return self.turn_to_goal_heading(pose);
        }
        let Some(progress) = self.tracker.update(pose, trajectory) else {
            return stopped(FollowStatus::NoTrajectory);
        };
        self.progress = Some(progress);
        self.squares += progress.cross_track * progress.cross_track;
        self.samples += 1;
        if progress.remaining <= Self::END_ZONE
            && progress.goal_distance <= self.config.goal_tolerance
        {
            self.at_goal = true;
            return self.turn_to_goal_heading(pose);
        }
        let mut reference = progress;
        reference.speed = reference.speed.max(self.config.min_speed);
        let raw = self.controller.step(pose, trajectory, &reference, dt);
        let twist = Twist::new(
            finite(raw.linear).clamp(-self.limits.max_linear, self.limits.max_linear),
            finite(raw.angular).clamp(-self.limits.max_angular, self.limits.max_angular),
        );
        FollowStep {
            twist,
            status: FollowStatus::Following {
                remaining: progress.remaining,
                eta: progress.eta,
                cross_track: progress.cross_track,
            },
        }
    }

    /// At the goal: turn in place until the heading is within `yaw_tolerance` of the goal
    /// heading (Nav2's goal checker: position first, then yaw), then arrived.
    fn turn_to_goal_heading(&mut self, pose: Pose2) -> FollowStep {
        let error = self
            .goal_heading
            .map_or(0.0, |h| crate::geometry::wrap_angle(h - pose.theta));
        if error.abs() <= self.config.yaw_tolerance {
            self.arrived = true;
            return stopped(FollowStatus::Arrived);
        }
        let top = self.config.rotate_speed.min(self.limits.max_angular);
        // A proportional turn (the error halves in about 0.35 s), capped at the rotate speed.
        let angular = (TURN_GAIN * error).clamp(-top, top);
        FollowStep {
            twist: Twist::new(0.0, angular),
            status: FollowStatus::Turning { error },
        }
    }

    fn restart(&mut self) {
        self.tracker.reset();
        self.controller.reset();
        self.progress = None;
        self.at_goal = false;
        self.arrived = false;
        self.squares = 0.0;
        self.samples = 0;
    }
}

fn build(kind: ControllerKind, config: &FollowConfig, limits: Limits) -> Box<dyn PathController> {
    match kind {
        ControllerKind::Pid => Box::new(PidFollower::new(config.pid.clone(), limits)),
        ControllerKind::PurePursuit => Box::new(PurePursuit::new(config.pure_pursuit.clone())),
        ControllerKind::Hybrid => Box::new(Hybrid::new(config.hybrid.clone(), limits)),
    }
}

fn stopped(status: FollowStatus) -> FollowStep {
    FollowStep {
        twist: Twist::ZERO,
        status,
    }
}

/// A NaN command becomes a stop rather than reaching the motors.
fn finite(x: f64) -> f64 {
    if x.is_finite() { x } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control::test_paths::{arc, line};
    use std::f64::consts::PI;

    fn follower(kind: ControllerKind) -> Follower {
        let config = FollowConfig {
            controller: kind,
            ..FollowConfig::default()
        };
        Follower::new(config, 0.4, 4.0)
    }

    #[test]
    fn with_a_goal_heading_it_turns_in_place_at_the_goal_then_arrives() {
        let mut f = follower(ControllerKind::Hybrid);
        f.set_goal_heading(Some(PI / 2.0));
        f.set_trajectory(line(1.0));
        // At the end of the line, facing along it: a quarter turn left is due.
        let mut pose = Pose2::new(1.0, 0.0, 0.0);
        let first = f.step(pose, 0.1);
        assert!(matches!(first.status, FollowStatus::Turning { error } if error > 1.5));
        assert_eq!(first.twist.linear, 0.0);
        assert!(first.twist.angular > 0.0);
        let mut steps = 0;
        loop {
            let step = f.step(pose, 0.1);
            if step.status == FollowStatus::Arrived {
                break;
            }
            pose.theta += step.twist.angular * 0.1;
            steps += 1;
            assert!(steps < 100, "never faced the goal heading");
        }
        assert!((pose.theta - PI / 2.0).abs() <= FollowConfig::default().yaw_tolerance);
        assert_eq!(f.step(pose, 0.1).twist, Twist::ZERO);
    }

    #[test]
    fn without_a_goal_heading_it_arrives_facing_any_way() {
        let mut f = follower(ControllerKind::Hybrid);
        f.set_trajectory(line(1.0));
        let step = f.step(Pose2::new(1.0, 0.0, 2.0), 0.1);
        assert_eq!(step.status, FollowStatus::Arrived);
    }

    #[test]
    fn a_loop_is_not_finished_at_its_start() {
        let mut f = follower(ControllerKind::Hybrid);
        f.set_trajectory(arc(0.5, 2.0 * PI * 0.5));
        let step = f.step(Pose2::new(0.0, 0.0, 0.0), 0.1);
        assert!(
            matches!(step.status, FollowStatus::Following { .. }),
            "{step:?}"
        );
        assert!(step.twist.linear > 0.0);
    }

    #[test]
    fn cross_track_rms_accumulates_over_steps() {
        let mut f = follower(ControllerKind::PurePursuit);
        assert_eq!(f.cross_track_rms(), None);
        f.set_trajectory(line(2.0));
        f.step(Pose2::new(0.5, -0.03, 0.0), 0.1);
        f.step(Pose2::new(0.6, 0.04, 0.0), 0.1);
        let rms = f.cross_track_rms().unwrap();
        assert!((rms - (0.0025_f64 / 2.0).sqrt()).abs() < 1e-12, "{rms}");
        f.set_trajectory(line(1.0));
        assert_eq!(f.cross_track_rms(), None, "a new path starts a new measure");
    }

    #[test]
    fn output_is_clamped_to_the_given_limits() {
        let mut f = Follower::new(FollowConfig::default(), 0.05, 0.5);
        f.set_controller(ControllerKind::Pid);
        f.set_trajectory(line(2.0));
        let step = f.step(Pose2::new(0.0, 0.0, 2.5), 0.1);
        assert_eq!(step.twist.angular, -0.5);
        let mut f = Follower::new(FollowConfig::default(), 0.05, 0.5);
        f.set_trajectory(line(2.0));
        for _ in 0..20 {
            assert!(f.step(Pose2::new(0.5, 0.0, 0.0), 0.1).twist.linear <= 0.05);
        }
    }

    #[test]
    fn switching_controller_starts_it_afresh() {
        let mut f = follower(ControllerKind::Hybrid);
        f.set_trajectory(line(2.0));
        let pose = Pose2::new(0.5, 0.0, 0.0);
        let first = f.step(pose, 0.1).twist.linear;
        assert!(f.step(pose, 0.1).twist.linear > first);
        f.set_controller(ControllerKind::Hybrid);
        assert_eq!(f.step(pose, 0.1).twist.linear, first, "smoothing restarted");
        f.set_controller(ControllerKind::PurePursuit);
        assert_eq!(f.controller(), ControllerKind::PurePursuit);
    }
}
