//! `[safety.health]`: how long each sensor may stay silent before it counts as lost, and how
//! slowly the robot drives while the lidar is lost (seed 000 §6.4.2: "LiDAR signal loss:
//! Immediate safety mode transition").
//!
//! ```toml
//! [safety.health]
//! odometry_timeout = 0.3
//! lidar_timeout = 1.0
//! camera_timeout = 1.0
//! arm_timeout = 1.0
//! slow_linear = 0.1
//! slow_angular = 0.6
//! ```

use crate::data::check::{self, Invalid};
use serde::{Deserialize, Serialize};

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct HealthConfig {
    /// Seconds without wheel travel before odometry counts as lost (the robot stops).
    pub odometry_timeout: f64,
    /// Seconds without a scan before the lidar counts as lost.
    pub lidar_timeout: f64,
    /// Seconds without a usable camera frame (none, or a dark or failed one) before the
    /// camera counts as lost.
    pub camera_timeout: f64,
    /// Seconds without the arm's joint states before the arm counts as lost.
    pub arm_timeout: f64,
    /// The lidar-lost safety mode's speed limits, m/s and rad/s.
    pub slow_linear: f64,
    pub slow_angular: f64,
}

impl Default for HealthConfig {
    fn default() -> Self {
        Self {
            odometry_timeout: 0.3,
            lidar_timeout: 1.0,
            camera_timeout: 1.0,
            arm_timeout: 1.0,
            slow_linear: 0.1,
            slow_angular: 0.6,
        }
    }
}

impl HealthConfig {
    /// The first bad field, named within `[safety]` (`health.lidar_timeout`).
    pub fn validate(&self) -> Result<(), Invalid> {
        check::within(&[
            ("health.odometry_timeout", self.odometry_timeout, 0.05, 60.0),
            ("health.lidar_timeout", self.lidar_timeout, 0.05, 60.0),
            ("health.camera_timeout", self.camera_timeout, 0.05, 60.0),
            ("health.arm_timeout", self.arm_timeout, 0.05, 60.0),
            ("health.slow_linear", self.slow_linear, 0.0, 5.0),
            ("health.slow_angular", self.slow_angular, 0.0, 20.0),
        ])
    }
}
