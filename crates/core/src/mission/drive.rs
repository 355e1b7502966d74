//! Small motions the mission drives itself: turns in place measured on the filter's
//! heading, turning to face a heading, and waiting for the gripper.

use super::config::{FACE_TOLERANCE, MissionConfig};
use crate::data::GripperState;
use crate::geometry::{Point2, Pose2, Twist, wrap_angle};

/// A turn in place by a given angle, counted from the heading changes step by step.
#[derive(Clone, Debug)]
pub(crate) struct Turn {
    previous: f64,
    turned: f64,
    angle: f64,
    started: f64,
    /// Give up counting after this long (a robot that does not turn must not hang the
    /// mission).
    limit: f64,
}

impl Turn {
    /// A turn of `angle` radians (positive) at `rate` rad/s from `pose` at `t`.
    pub fn new(pose: Pose2, t: f64, angle: f64, rate: f64) -> Self {
        Self {
            previous: pose.theta,
            turned: 0.0,
            angle,
            started: t,
            limit: 2.0 * angle / rate + 2.0,
        }
    }

    /// A full turn: navdeck's scan, in place of seed 001 section 7's 30 s rotation.
    pub fn full(pose: Pose2, t: f64, rate: f64) -> Self {
        Self::new(pose, t, 2.0 * std::f64::consts::PI, rate)
    }

    /// Notes the new heading; true once the turn is complete.
    pub fn advance(&mut self, pose: Pose2, t: f64) -> bool {
        self.turned += wrap_angle(pose.theta - self.previous).abs();
        self.previous = pose.theta;
        self.turned >= self.angle - 1e-6 || t - self.started >= self.limit
    }

    /// Fraction of the turn done, 0..1.
    pub fn progress(&self) -> f64 {
        (self.turned / self.angle).min(1.0)
    }
}

/// The twist that turns towards a heading error `error`: proportional, at least a slow
/// creep so a small error still closes, at most the scan speed.
pub(crate) fn turn_towards(error: f64, config: &MissionConfig) -> Twist {
    let rate = (1.5 * error.abs()).clamp(0.1, config.scan_speed);
    Twist::new(0.0, rate * error.signum())
}

/// Whether a heading error is small enough to count as facing.
pub(crate) fn faces(error: f64) -> bool {
    error.abs() < FACE_TOLERANCE
}

/// Steering while driving straight at something: a gentle proportional correction.
pub(crate) fn steer(error: f64) -> f64 {
    (1.0 * error).clamp(-0.3, 0.3)
}

/// The bearing of `target` from `pose`, relative to its heading, radians.
pub(crate) fn bearing(pose: Pose2, target: Point2) -> f64 {
    wrap_angle((target.y - pose.y).atan2(target.x - pose.x) - pose.theta)
}

/// The point `distance` metres from `p` towards `from`.
pub(crate) fn towards(p: Point2, from: Point2, distance: f64) -> Point2 {
    let d = p.distance(from);
    if d < 1e-9 {
        return p;
    }
    let k = distance.min(d) / d;
    Point2::new(p.x + k * (from.x - p.x), p.y + k * (from.y - p.y))
}

/// What waiting for the gripper to open has come to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Wait {
    Waiting,
    Done,
    /// Timed out without the state confirming it.
    TimedOut,
}

/// Waiting for the gripper to open: done when it reports Open, or after seed 001's wait
/// when it reports nothing; timed out a second later.
pub(crate) fn opened(state: Option<GripperState>, waited: f64, config: &MissionConfig) -> Wait {
    match state {
        Some(GripperState::Open) => Wait::Done,
        None if waited >= config.gripper_wait => Wait::Done,
        _ if waited >= config.gripper_wait + 1.0 => Wait::TimedOut,
        _ => Wait::Waiting,
    }
}
