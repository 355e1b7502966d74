//! Path-following parameters: the `[follow]` section, defaults from the seeds where they
//! give one.

use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// Which path-following law drives the robot.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ControllerKind {
    /// Heading PID towards the next waypoint (seed 001 section 6).
    Pid,
    /// Pure pursuit of a look-ahead point (seed 003 `calculate_forward`).
    PurePursuit,
    /// Curvature feed-forward plus a PID on the look-ahead angle (seed 004 section C).
    #[default]
    Hybrid,
}

impl ControllerKind {
    pub const ALL: [ControllerKind; 3] = [Self::Pid, Self::PurePursuit, Self::Hybrid];

    /// The config and command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Pid => "pid",
            Self::PurePursuit => "pure_pursuit",
            Self::Hybrid => "hybrid",
        }
    }

    /// A label for the screen.
    pub fn label(self) -> &'static str {
        match self {
            Self::Pid => "PID",
            Self::PurePursuit => "Pure pursuit",
            Self::Hybrid => "Hybrid",
        }
    }
}

impl fmt::Display for ControllerKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The name was none of "pid", "pure_pursuit", "hybrid".
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown controller `{0}` (expected pid, pure_pursuit or hybrid)")]
pub struct UnknownController(pub String);

impl FromStr for ControllerKind {
    type Err = UnknownController;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| UnknownController(s.to_string()))
    }
}

/// The `[follow]` section.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct FollowConfig {
    pub controller: ControllerKind,
    /// Arrived when this close to the goal, metres (seed 001 section 6 drops a waypoint at 5 cm).
    pub goal_tolerance: f64,
    /// With a goal heading (a goal pose), arrived when facing within this of it, radians
    /// (Nav2's SimpleGoalChecker `yaw_goal_tolerance`: 0.25).
    pub yaw_tolerance: f64,
    /// Fastest turn in place to a goal's heading, rad/s (Nav2's RotationShimController
    /// `rotate_to_heading_angular_vel`: 1.8), within the robot's own limit.
    pub rotate_speed: f64,
    /// Floor on the reference speed, m/s: the profile ends at 0, the robot must still arrive.
    pub min_speed: f64,
    /// While following, the forward command is cut when keeping it up until the robot
    /// could brake would bring the footprint within this distance of a lidar-mapped
    /// obstacle, metres: a 1 cm map cell's quantisation and the estimate's centimetre or
    /// two (navdeck's; Nav2's collision monitor stops on a polygon a margin beyond the
    /// footprint). 0 turns the guard off.
    pub stop_margin: f64,
    pub pid: PidFollowConfig,
    pub pure_pursuit: PurePursuitConfig,
    pub hybrid: HybridConfig,
}

impl Default for FollowConfig {
    fn default() -> Self {
        Self {
            controller: ControllerKind::Hybrid,
            goal_tolerance: 0.05,
            yaw_tolerance: 0.25,
            rotate_speed: 1.8,
            min_speed: 0.03,
            stop_margin: 0.03,
            pid: PidFollowConfig::default(),
            pure_pursuit: PurePursuitConfig::default(),
            hybrid: HybridConfig::default(),
        }
    }
}

/// Waypoint PID (seed 001 section 6).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PidFollowConfig {
    /// Heading gains (seed 001 section 6: Kp 0.5, Ki 0.01, Kd 0.3).
    pub kp: f64,
    pub ki: f64,
    pub kd: f64,
    /// Bound on the integral of the heading error, rad*s (anti-windup; the seed has none).
    pub integral_limit: f64,
    /// Stop and turn in place above this heading error, degrees (seed 001 section 6: 60;
    /// the seed applies it to the PID output).
    pub stop_turn_deg: f64,
    /// A waypoint closer than this is done, metres (seed 001 section 6: 5 cm).
    pub waypoint_radius: f64,
    /// The trajectory is decimated to waypoints this far apart, metres.
    pub waypoint_spacing: f64,
}

impl Default for PidFollowConfig {
    fn default() -> Self {
        Self {
            kp: 0.5,
            ki: 0.01,
            kd: 0.3,
            integral_limit: 1.0,
            stop_turn_deg: 60.0,
            waypoint_radius: 0.05,
            waypoint_spacing: 0.10,
        }
    }
}

/// Pure pursuit (seed 003 `calculate_forward`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PurePursuitConfig {
    /// Shortest look-ahead, metres (seed 003: `max(distance, 0.4)`).
    pub min_lookahead: f64,
    /// Multiplies the commanded turn rate (seed 003: 1.0 driving forward).
    pub gain: f64,
    /// No turning while the look-ahead point is this close to straight ahead, metres
    /// (seed 003: |lateral| < 0.005).
    pub deadband: f64,
    /// Turn-rate clip, rad/s. Seed 003 clips at 0.3 on straight tag-to-tag legs at 0.3 m/s;
    /// that allows no radius under 1 m, so the default leaves room for the planner's curves
    /// (radius 0.13 m at 0.2 m/s). Also the rate of turning in place while the look-ahead
    /// point lies behind the robot.
    pub max_angular: f64,
    /// Within this distance of the goal the turn rate scales down linearly, metres (seed 003: 0.3).
    pub slow_radius: f64,
}

impl Default for PurePursuitConfig {
    fn default() -> Self {
        Self {
            min_lookahead: 0.4,
            gain: 1.0,
            deadband: 0.005,
            max_angular: 1.5,
            slow_radius: 0.3,
        }
    }
}

/// Feed-forward plus PID (seed 004 section C).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct HybridConfig {
    /// Distance of the target along the path, metres (seed 004 section C: 0.6).
    pub lookahead: f64,
    /// Gains on the look-ahead angle error (seed 004 section C: Kp 1.8, Ki 0.0, Kd 0.04).
    pub kp: f64,
    pub ki: f64,
    pub kd: f64,
    /// Speed scales with max(0, cos(error)) to this power (seed 004 section C: 0.9).
    pub heading_exponent: f64,
    /// Speed rate limit, m/s^2 (seed 004 section C: 0.6).
    pub max_accel: f64,
    /// Weight of the new speed in the exponential smoothing (seed 004 section C: 0.45).
    pub smoothing: f64,
}

impl Default for HybridConfig {
    fn default() -> Self {
        Self {
            lookahead: 0.6,
            kp: 1.8,
            ki: 0.0,
            kd: 0.04,
            heading_exponent: 0.9,
            max_accel: 0.6,
            smoothing: 0.45,
        }
    }
}

/// A refused value: the field's path within `[follow]`, its value and why.
pub use crate::data::check::Invalid;

impl FollowConfig {
    /// Checks signs and ranges a parser cannot.
    pub fn validate(&self) -> Result<(), Invalid> {
        let (pid, pp, hy) = (&self.pid, &self.pure_pursuit, &self.hybrid);
        crate::data::check::within(&[
            ("goal_tolerance", self.goal_tolerance, 0.001, 2.0),
            ("yaw_tolerance", self.yaw_tolerance, 0.001, 3.2),
            ("rotate_speed", self.rotate_speed, 0.01, 20.0),
            ("min_speed", self.min_speed, 0.001, 5.0),
            ("stop_margin", self.stop_margin, 0.0, 1.0),
            ("pid.kp", pid.kp, 0.0, 100.0),
            ("pid.ki", pid.ki, 0.0, 100.0),
            ("pid.kd", pid.kd, 0.0, 100.0),
            ("pid.integral_limit", pid.integral_limit, 0.001, 100.0),
            ("pid.waypoint_radius", pid.waypoint_radius, 0.001, 2.0),
            ("pid.waypoint_spacing", pid.waypoint_spacing, 0.001, 5.0),
            ("pure_pursuit.min_lookahead", pp.min_lookahead, 0.01, 5.0),
            ("pure_pursuit.gain", pp.gain, 0.01, 100.0),
            ("pure_pursuit.deadband", pp.deadband, 0.0, 1.0),
            ("pure_pursuit.max_angular", pp.max_angular, 0.01, 20.0),
            ("pure_pursuit.slow_radius", pp.slow_radius, 0.001, 5.0),
            ("hybrid.lookahead", hy.lookahead, 0.01, 5.0),
            ("hybrid.kp", hy.kp, 0.0, 100.0),
            ("hybrid.ki", hy.ki, 0.0, 100.0),
            ("hybrid.kd", hy.kd, 0.0, 100.0),
            ("hybrid.heading_exponent", hy.heading_exponent, 0.01, 10.0),
            ("hybrid.max_accel", hy.max_accel, 0.01, 20.0),
        ])?;
        let turn = self.pid.stop_turn_deg;
        if !(turn > 0.0 && turn <= 180.0) {
            return Err(("pid.stop_turn_deg", turn, "must lie in (0, 180]".into()));
        }
        let smoothing = self.hybrid.smoothing;
        if !(smoothing > 0.0 && smoothing <= 1.0) {
            return Err(("hybrid.smoothing", smoothing, "must lie in (0, 1]".into()));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_carry_the_seed_gains_and_validate() {
        let c = FollowConfig::default();
        assert_eq!((c.pid.kp, c.pid.ki, c.pid.kd), (0.5, 0.01, 0.3));
        assert_eq!((c.hybrid.kp, c.hybrid.ki, c.hybrid.kd), (1.8, 0.0, 0.04));
        assert_eq!(c.pure_pursuit.min_lookahead, 0.4);
        assert_eq!(c.controller, ControllerKind::Hybrid);
        assert_eq!(c.validate(), Ok(()));
    }

    #[test]
    fn controller_names_round_trip_through_toml_and_from_str() {
        let c: FollowConfig = toml::from_str("controller = \"pure_pursuit\"\n").unwrap();
        assert_eq!(c.controller, ControllerKind::PurePursuit);
        for kind in ControllerKind::ALL {
            assert_eq!(kind.name().parse::<ControllerKind>(), Ok(kind));
        }
        let err = "purepursuit".parse::<ControllerKind>().unwrap_err();
        assert!(err.to_string().contains("purepursuit"));
    }

    #[test]
    fn unknown_field_and_bad_values_are_refused_by_name() {
        assert!(toml::from_str::<FollowConfig>("[hybrid]\nlookahed = 0.5\n").is_err());
        let mut c = FollowConfig::default();
        c.hybrid.smoothing = 1.5;
        assert_eq!(c.validate().unwrap_err().0, "hybrid.smoothing");
        c.hybrid.smoothing = 0.45;
        c.hybrid.lookahead = f64::NAN;
        assert_eq!(c.validate().unwrap_err().0, "hybrid.lookahead");
        c.hybrid.lookahead = 0.6;
        c.pid.kd = -0.3;
        assert_eq!(
            c.validate().unwrap_err(),
            ("pid.kd", -0.3, "must lie in 0..=100".into())
        );
    }
}
