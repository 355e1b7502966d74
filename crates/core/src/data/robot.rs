//! `[robot]`: the robot's geometry and limits, which every layer reads.

use crate::geometry::Twist;
use serde::{Deserialize, Serialize};

/// The differential-drive base (seed 001 "Robot Configuration").
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RobotConfig {
    /// Wheel radius in metres (seed 001: 0.027216).
    pub wheel_radius: f64,
    /// Distance between the wheels in metres (seed 001 `width`: 0.11).
    pub track: f64,
    /// Control loop period in seconds (seed 001 `delta_t`: 0.1).
    pub control_period: f64,
    /// Radius of the robot's footprint for collisions, metres.
    pub footprint_radius: f64,
    /// Hard limits the base can reach: m/s and rad/s.
    pub max_linear: f64,
    pub max_angular: f64,
    /// Acceleration limits: m/s^2 and rad/s^2.
    pub max_linear_accel: f64,
    pub max_angular_accel: f64,
}

impl Default for RobotConfig {
    fn default() -> Self {
        Self {
            wheel_radius: 0.027216,
            track: 0.11,
            control_period: 0.1,
            footprint_radius: 0.08,
            max_linear: 0.4,
            max_angular: 4.0,
            max_linear_accel: 1.0,
            max_angular_accel: 8.0,
        }
    }
}

impl RobotConfig {
    /// The requested twist clipped to the base's top speeds; NaN or infinite parts become 0.
    pub fn clamp_twist(&self, cmd: Twist) -> Twist {
        let clip = |v: f64, max: f64| {
            if v.is_finite() {
                v.clamp(-max, max)
            } else {
                0.0
            }
        };
        Twist::new(
            clip(cmd.linear, self.max_linear),
            clip(cmd.angular, self.max_angular),
        )
    }

    /// Moves the base's twist `current` toward `target` by at most `h` seconds' worth of
    /// acceleration per axis.
    pub fn ramp(&self, current: Twist, target: Twist, h: f64) -> Twist {
        let toward =
            |from: f64, to: f64, max_step: f64| from + (to - from).clamp(-max_step, max_step);
        Twist::new(
            toward(current.linear, target.linear, self.max_linear_accel * h),
            toward(current.angular, target.angular, self.max_angular_accel * h),
        )
    }

    /// Checks what the parser cannot: every size, period and limit positive.
    pub fn validate(&self) -> Result<(), super::check::Invalid> {
        // Bounds: a small wheeled robot, from a 1 cm toy to a 2 m cart.
        super::check::within(&[
            ("wheel_radius", self.wheel_radius, 0.005, 0.5),
            ("track", self.track, 0.02, 2.0),
            ("control_period", self.control_period, 0.005, 1.0),
            ("footprint_radius", self.footprint_radius, 0.01, 2.0),
            ("max_linear", self.max_linear, 0.01, 5.0),
            ("max_angular", self.max_angular, 0.1, 20.0),
            ("max_linear_accel", self.max_linear_accel, 0.01, 20.0),
            ("max_angular_accel", self.max_angular_accel, 0.1, 100.0),
        ])
    }

    /// The fastest a wheel is ever asked to turn, v + w b / 2, with half again for
    /// overshoot, m/s: wheel travel beyond this between two readings is a bad reading.
    pub fn max_wheel_speed(&self) -> f64 {
        1.5 * (self.max_linear + self.max_angular * self.track / 2.0)
    }
}
