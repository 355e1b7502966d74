//! Small motions the mission drives itself: turns in place measured on the filter's
//! heading, turning to face a heading, and waiting for the gripper.

use super::config::{BACK_OFF_SPEED, FACE_TOLERANCE, MissionConfig};
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

/// A creep covers its last this many metres at the final approach speed, where what
/// stops it is decided (navdeck's: a second of seed 001's slow approach).
pub(crate) const SLOW_FOR: f64 = 0.05;
/// Braking onto the approach speed, m/s² (seed 004's a_max).
const BRAKE: f64 = 0.6;

/// A creep's forward speed with `remaining` metres to where it stops: the final approach
/// speed for the last `SLOW_FOR`, and before that up to the back-off speed (seed 001
/// section 8 drives forward and back at one speed), braking onto the slow speed as seed
/// 004's backward pass does: v = sqrt(v_end² + 2·a_max·Δs).
fn creep_speed(remaining: f64, config: &MissionConfig) -> f64 {
    let slow = config.approach_speed;
    let braking = (remaining - SLOW_FOR).max(0.0);
    (slow * slow + 2.0 * BRAKE * braking)
        .sqrt()
        .min(BACK_OFF_SPEED.max(slow))
}

/// A creep's pace over its whole course: `creep_speed` of what remains, and never faster
/// again once it has slowed. A target whose estimate jumps further away (a block's outline
/// lost, its markers' estimate a few centimetres off) is turned towards slowly, in reach.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Pace {
    slowest: f64,
}

impl Pace {
    pub fn new() -> Self {
        Self {
            slowest: f64::INFINITY,
        }
    }

    /// The speed with `remaining` metres to go.
    pub fn speed(&mut self, remaining: f64, config: &MissionConfig) -> f64 {
        self.slowest = creep_speed(remaining, config).min(self.slowest);
        self.slowest
    }
}

/// A creep's twist at `speed` towards a bearing `error`: seed 001's slow approach
/// steered as `steer` does, faster only along the same arc (the turn rate scales with the
/// speed, so the curvature, and where the creep ends up, do not change with it).
pub(crate) fn creep_twist(speed: f64, error: f64, config: &MissionConfig) -> Twist {
    Twist::new(speed, steer(error) * speed / config.approach_speed)
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_creep_runs_at_the_back_off_speed_slows_for_its_last_5_cm_and_stays_slow() {
        let config = MissionConfig::default();
        let mut pace = Pace::new();
        assert_eq!(pace.speed(0.20, &config), BACK_OFF_SPEED);
        assert_eq!(pace.speed(0.04, &config), config.approach_speed);
        // Its target's estimate jumped 15 cm further off: it does not speed up again.
        assert_eq!(pace.speed(0.19, &config), config.approach_speed);
        // Braking onto the slow speed takes a few millimetres (seed 004's a_max).
        let braking = creep_speed(SLOW_FOR + 0.004, &config);
        assert!(braking > config.approach_speed && braking < BACK_OFF_SPEED);
    }
}
