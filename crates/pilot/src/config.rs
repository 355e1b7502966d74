//! The pilot's own sections, `[teleop]` and `[race]`, and the settings it runs on: every
//! section of the config that decides how the robot moves.

use navdeck_core::control::config::FollowConfig;
use navdeck_core::data::check::{self, Invalid};
use navdeck_core::data::robot::RobotConfig;
use navdeck_core::map::config::MapConfig;
use navdeck_core::mission::config::MissionConfig;
use navdeck_core::plan::config::PlanConfig;
use navdeck_core::slam::config::SlamConfig;
use navdeck_core::slam::mcl::config::LocalizationConfig;
use serde::{Deserialize, Serialize};

/// The sections the pilot reads, taken from the session's config.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Settings {
    pub robot: RobotConfig,
    pub teleop: TeleopConfig,
    pub race: RaceConfig,
    pub slam: SlamConfig,
    pub map: MapConfig,
    pub plan: PlanConfig,
    pub follow: FollowConfig,
    pub mission: MissionConfig,
    pub localization: LocalizationConfig,
    pub lidar_slam: navdeck_core::slam::lidar::LidarSlamConfig,
    /// The arm, when the robot has one.
    pub arm: Option<navdeck_core::arm::ArmConfig>,
    /// The collision monitor's zones (`[safety]`).
    pub safety: navdeck_core::control::collision_monitor::SafetyConfig,
    /// Lane following's gains and stops (`[lane.drive]`).
    pub lane: navdeck_core::control::lane::LaneDriveConfig,
}

/// Race mode (seed 001: "High-speed mode (reduced SLAM updates)").
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RaceConfig {
    /// Drive speeds on entering race mode, m/s and rad/s; the limits are the robot's.
    pub linear_speed: f64,
    pub angular_speed: f64,
    /// Correct with every k-th camera frame only.
    pub correct_every: u32,
    /// Within a used frame, only the m nearest sightings (0: all of them).
    pub nearest: u32,
    /// Warn when the position's standard deviation grows past this, metres.
    pub sigma_warning: f64,
}

impl Default for RaceConfig {
    fn default() -> Self {
        Self {
            linear_speed: 0.3,
            angular_speed: 3.0,
            correct_every: 3,
            nearest: 0,
            sigma_warning: 0.05,
        }
    }
}

/// Keyboard driving (teleop_twist_keyboard habits plus a deadman).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TeleopConfig {
    /// Speed a drive key asks for at start, m/s.
    pub linear_speed: f64,
    /// Turn rate a turn key asks for at start, rad/s.
    pub angular_speed: f64,
    /// Factor applied by the speed up/down keys (teleop_twist_keyboard uses 10 %).
    pub speed_step: f64,
    /// Stop when no key event arrived for this long, seconds.
    pub deadman_timeout: f64,
    /// Manual mode's speed limits, m/s and rad/s; race mode may go up to the robot's.
    pub max_linear: f64,
    pub max_angular: f64,
}

impl Default for TeleopConfig {
    fn default() -> Self {
        Self {
            linear_speed: 0.15,
            angular_speed: 1.5,
            speed_step: 1.1,
            deadman_timeout: 0.5,
            max_linear: 0.25,
            max_angular: 2.5,
        }
    }
}

impl RaceConfig {
    /// Checks what the parser cannot.
    pub fn validate(&self) -> Result<(), Invalid> {
        check::within(&[
            ("linear_speed", self.linear_speed, 0.001, 5.0),
            ("angular_speed", self.angular_speed, 0.01, 20.0),
            ("sigma_warning", self.sigma_warning, 0.0001, 10.0),
        ])?;
        check::counts_within(&[
            ("correct_every", u64::from(self.correct_every), 1, 1_000_000),
            ("nearest", u64::from(self.nearest), 0, 1000),
        ])
    }
}

impl TeleopConfig {
    /// Checks what the parser cannot.
    pub fn validate(&self) -> Result<(), Invalid> {
        check::within(&[
            ("linear_speed", self.linear_speed, 0.001, 5.0),
            ("angular_speed", self.angular_speed, 0.01, 20.0),
            // A factor above 1, at most quadrupling per press.
            ("speed_step", self.speed_step, 1.001, 4.0),
            ("deadman_timeout", self.deadman_timeout, 0.05, 10.0),
            ("max_linear", self.max_linear, 0.001, 5.0),
            ("max_angular", self.max_angular, 0.01, 20.0),
        ])
    }
}
