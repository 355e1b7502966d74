//! Robot, teleop and twin parameters: TOML with every field defaulted from the seed robot.
//!
//! A config file names only what it changes; an unknown field or a bad value is refused
//! with the file, line and field in the message.

use crate::control::config::FollowConfig;
use crate::link::serial::config::SerialConfig;
use crate::map::config::MapConfig;
use crate::mission::config::MissionConfig;
use crate::perception::config::VisionConfig;
use crate::plan::config::PlanConfig;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Why a config file was refused.
#[derive(Debug, thiserror::Error)]
pub enum ConfigError {
    #[error("cannot read config {path}: {error}")]
    Read {
        path: PathBuf,
        error: std::io::Error,
    },
    #[error("config {path}: {message}")]
    Parse { path: PathBuf, message: String },
    #[error("config {path}: field `{field}` = {value}: {reason}")]
    Invalid {
        path: PathBuf,
        field: String,
        value: String,
        reason: &'static str,
    },
}

/// Everything a session can configure; each section has seed-derived defaults.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Config {
    pub robot: RobotConfig,
    pub teleop: TeleopConfig,
    pub slam: SlamConfig,
    pub race: RaceConfig,
    pub sim: SimConfig,
    pub map: MapConfig,
    pub plan: PlanConfig,
    pub follow: FollowConfig,
    pub mission: MissionConfig,
    /// `--link ros2`: topics, QoS, message variants.
    pub ros2: crate::link::ros2::config::Ros2Config,
    pub serial: SerialConfig,
    pub vision: VisionConfig,
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

/// EKF-SLAM noise and landmark management (seed 001 `ekf_slam` and "Landmark Management").
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SlamConfig {
    /// Wheel rotation noise, degrees per revolution of the wheel (seed 001 `motor_std`: 4).
    pub motor_std_deg: f64,
    /// Range noise, metres (seed 001 `dist_std`: 0.1).
    pub dist_std: f64,
    /// Bearing noise, degrees (seed 001 `angle_std`: 4).
    pub angle_std_deg: f64,
    /// Sightings of an ID before it enters the state (seed 001: "1+").
    pub min_sightings: u32,
    /// `Some(v)`: new landmarks start with variance v m^2 and no correlation (seed 001: 0.5);
    /// `None`: the uncertainty is propagated through the inverse observation model.
    pub fixed_initial_variance: Option<f64>,
    /// Mahalanobis gate on a sighting's innovation, chi-square with 2 degrees of freedom
    /// (13.82 rejects 0.1 % of good sightings).
    pub gate_chi2: f64,
}

impl Default for SlamConfig {
    fn default() -> Self {
        Self {
            motor_std_deg: 4.0,
            dist_std: 0.1,
            angle_std_deg: 4.0,
            min_sightings: 1,
            fixed_initial_variance: None,
            gate_chi2: 13.82,
        }
    }
}

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
    /// The fastest a wheel is ever asked to turn, v + w b / 2, with half again for
    /// overshoot, m/s: wheel travel beyond this between two readings is a bad reading.
    pub fn max_wheel_speed(&self) -> f64 {
        1.5 * (self.max_linear + self.max_angular * self.track / 2.0)
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

/// The digital twin's sensors and physics.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SimConfig {
    pub physics: PhysicsConfig,
    pub encoders: EncoderConfig,
    pub camera: CameraConfig,
    pub lidar: LidarConfig,
    pub gripper: GripperConfig,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PhysicsConfig {
    /// Integration step of the twin, seconds.
    pub step: f64,
}

impl Default for PhysicsConfig {
    fn default() -> Self {
        Self { step: 0.01 }
    }
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct EncoderConfig {
    /// Counts per wheel revolution (an EV3 motor reports degrees: 360).
    pub ticks_per_rev: u32,
    /// Multiplicative noise on each wheel's travel, as a standard deviation (0.02 = 2 %).
    pub noise_std: f64,
    /// Probability per physics step that a wheel slips and loses `slip_fraction` of its travel.
    pub slip_probability: f64,
    pub slip_fraction: f64,
}

impl Default for EncoderConfig {
    fn default() -> Self {
        Self {
            ticks_per_rev: 360,
            noise_std: 0.02,
            slip_probability: 0.001,
            slip_fraction: 0.5,
        }
    }
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CameraConfig {
    /// Horizontal field of view in degrees: 2 atan(432 / 635.93) from seed 001's intrinsics at 864 px.
    pub fov_deg: f64,
    pub min_range: f64,
    pub max_range: f64,
    /// A marker seen further than this from face-on is not detected, degrees.
    pub max_view_angle_deg: f64,
    pub rate_hz: f64,
    /// Range noise, metres (seed 001 `dist_std`: 0.1).
    pub dist_std: f64,
    /// Bearing noise, degrees (seed 001 `angle_std`: 4).
    pub angle_std_deg: f64,
    /// Probability that a visible marker is missed in a frame.
    pub miss_probability: f64,
}

impl Default for CameraConfig {
    fn default() -> Self {
        Self {
            fov_deg: 68.4,
            min_range: 0.1,
            max_range: 3.0,
            max_view_angle_deg: 75.0,
            rate_hz: 10.0,
            dist_std: 0.1,
            angle_std_deg: 4.0,
            miss_probability: 0.05,
        }
    }
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LidarConfig {
    pub enabled: bool,
    /// Beams over a full turn (TurtleBot3's LDS-01: 360).
    pub beams: u32,
    pub min_range: f64,
    pub max_range: f64,
    pub rate_hz: f64,
    pub range_std: f64,
}

impl Default for LidarConfig {
    fn default() -> Self {
        Self {
            enabled: true,
            beams: 360,
            min_range: 0.12,
            max_range: 3.5,
            rate_hz: 5.0,
            range_std: 0.01,
        }
    }
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct GripperConfig {
    /// Time the jaws take to open or close, seconds (seed 001 waits 1 s).
    pub actuation_time: f64,
    /// The jaws' reach in front of the robot centre: a block whose centre lies within
    /// [near, far] ahead and `half_width` sideways is caught when they close.
    pub reach_near: f64,
    pub reach_far: f64,
    pub half_width: f64,
}

impl Default for GripperConfig {
    fn default() -> Self {
        Self {
            actuation_time: 1.0,
            reach_near: 0.06,
            reach_far: 0.14,
            half_width: 0.035,
        }
    }
}

impl Config {
    /// Reads and validates a config file.
    pub fn load(path: &Path) -> Result<Config, ConfigError> {
        let text = std::fs::read_to_string(path).map_err(|source| ConfigError::Read {
            path: path.to_path_buf(),
            error: source,
        })?;
        Self::parse(&text, path)
    }

    /// Parses config text; `path` only names the source in errors.
    pub fn parse(text: &str, path: &Path) -> Result<Config, ConfigError> {
        let config: Config = toml::from_str(text).map_err(|e| ConfigError::Parse {
            path: path.to_path_buf(),
            message: e.to_string().trim_end().to_string(),
        })?;
        config.validate(path)?;
        Ok(config)
    }

    /// Checks values a parser cannot: signs and ranges.
    pub fn validate(&self, path: &Path) -> Result<(), ConfigError> {
        let positive: [(&'static str, f64); 24] = [
            ("robot.wheel_radius", self.robot.wheel_radius),
            ("robot.track", self.robot.track),
            ("robot.control_period", self.robot.control_period),
            ("robot.footprint_radius", self.robot.footprint_radius),
            ("robot.max_linear", self.robot.max_linear),
            ("robot.max_angular", self.robot.max_angular),
            ("robot.max_linear_accel", self.robot.max_linear_accel),
            ("robot.max_angular_accel", self.robot.max_angular_accel),
            ("teleop.linear_speed", self.teleop.linear_speed),
            ("teleop.angular_speed", self.teleop.angular_speed),
            ("teleop.deadman_timeout", self.teleop.deadman_timeout),
            ("teleop.max_linear", self.teleop.max_linear),
            ("teleop.max_angular", self.teleop.max_angular),
            ("race.linear_speed", self.race.linear_speed),
            ("race.angular_speed", self.race.angular_speed),
            ("race.sigma_warning", self.race.sigma_warning),
            ("sim.physics.step", self.sim.physics.step),
            ("slam.dist_std", self.slam.dist_std),
            ("slam.angle_std_deg", self.slam.angle_std_deg),
            ("slam.gate_chi2", self.slam.gate_chi2),
            ("sim.camera.max_range", self.sim.camera.max_range),
            ("sim.camera.rate_hz", self.sim.camera.rate_hz),
            ("sim.lidar.max_range", self.sim.lidar.max_range),
            ("sim.lidar.rate_hz", self.sim.lidar.rate_hz),
        ];
        for (field, value) in positive {
            if !(value.is_finite() && value > 0.0) {
                return Err(invalid(path, field, value, "must be a positive number"));
            }
        }
        let probabilities = [
            (
                "sim.encoders.slip_probability",
                self.sim.encoders.slip_probability,
            ),
            (
                "sim.encoders.slip_fraction",
                self.sim.encoders.slip_fraction,
            ),
            (
                "sim.camera.miss_probability",
                self.sim.camera.miss_probability,
            ),
        ];
        for (field, value) in probabilities {
            if !(0.0..=1.0).contains(&value) {
                return Err(invalid(path, field, value, "must lie in 0..=1"));
            }
        }
        let non_negative = [
            ("sim.encoders.noise_std", self.sim.encoders.noise_std),
            ("sim.camera.dist_std", self.sim.camera.dist_std),
            ("sim.camera.angle_std_deg", self.sim.camera.angle_std_deg),
            ("sim.lidar.range_std", self.sim.lidar.range_std),
        ];
        for (field, value) in non_negative {
            if !(value.is_finite() && value >= 0.0) {
                return Err(invalid(path, field, value, "must be zero or more"));
            }
        }
        if self.teleop.speed_step <= 1.0 || !self.teleop.speed_step.is_finite() {
            return Err(invalid(
                path,
                "teleop.speed_step",
                self.teleop.speed_step,
                "must be a factor above 1",
            ));
        }
        if !(0.0..360.0).contains(&self.sim.camera.fov_deg) || self.sim.camera.fov_deg == 0.0 {
            return Err(invalid(
                path,
                "sim.camera.fov_deg",
                self.sim.camera.fov_deg,
                "must lie in (0, 360)",
            ));
        }
        if self.race.correct_every == 0 {
            return Err(invalid(
                path,
                "race.correct_every",
                0.0,
                "must be at least 1",
            ));
        }
        if self.sim.lidar.beams == 0 {
            return Err(invalid(path, "sim.lidar.beams", 0.0, "must be at least 1"));
        }
        let sections = [
            ("map", self.map.validate()),
            ("plan", self.plan.validate()),
            ("follow", self.follow.validate()),
            ("mission", self.mission.validate()),
            ("ros2", self.ros2.validate()),
            ("serial", self.serial.validate()),
            ("vision", self.vision.validate()),
        ];
        for (section, result) in sections {
            if let Err((field, value, reason)) = result {
                return Err(ConfigError::Invalid {
                    path: path.to_path_buf(),
                    field: format!("{section}.{field}"),
                    value: value.to_string(),
                    reason,
                });
            }
        }
        if self.sim.encoders.ticks_per_rev == 0 {
            return Err(invalid(
                path,
                "sim.encoders.ticks_per_rev",
                0.0,
                "must be at least 1",
            ));
        }
        Ok(())
    }
}

fn invalid(path: &Path, field: &str, value: f64, reason: &'static str) -> ConfigError {
    ConfigError::Invalid {
        path: path.to_path_buf(),
        field: field.to_string(),
        value: value.to_string(),
        reason,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_carry_seed_001_robot() {
        let c = Config::default();
        assert_eq!(c.robot.wheel_radius, 0.027216);
        assert_eq!(c.robot.track, 0.11);
        assert_eq!(c.robot.control_period, 0.1);
        assert_eq!(c.sim.camera.dist_std, 0.1);
        assert_eq!(c.sim.camera.angle_std_deg, 4.0);
    }

    #[test]
    fn partial_file_overrides_only_what_it_names() {
        let c = Config::parse("[sim.lidar]\nbeams = 90\n", Path::new("x.toml")).unwrap();
        assert_eq!(c.sim.lidar.beams, 90);
        assert_eq!(c.robot, RobotConfig::default());
    }

    #[test]
    fn unknown_field_is_named_with_its_line() {
        let err = Config::parse(
            "[robot]\ntrack = 0.2\nwheel_radus = 0.03\n",
            Path::new("bad.toml"),
        )
        .unwrap_err()
        .to_string();
        assert!(err.contains("bad.toml"), "{err}");
        assert!(err.contains("wheel_radus"), "{err}");
        assert!(err.contains("line 3"), "{err}");
    }

    #[test]
    fn negative_value_is_refused_with_field_and_value() {
        let err = Config::parse("[robot]\ntrack = -0.1\n", Path::new("neg.toml"))
            .unwrap_err()
            .to_string();
        assert!(err.contains("robot.track") && err.contains("-0.1"), "{err}");
    }

    #[test]
    fn planning_and_following_sections_are_checked_by_name() {
        let path = Path::new("nav.toml");
        let err = |text: &str| Config::parse(text, path).unwrap_err().to_string();
        let e = err("[plan]\nmax_speed = -0.2\n");
        assert!(e.contains("plan.max_speed") && e.contains("-0.2"), "{e}");
        let e = err("[follow.hybrid]\nsmoothing = 1.5\n");
        assert!(
            e.contains("follow.hybrid.smoothing") && e.contains("1.5"),
            "{e}"
        );
        let e = err("[map]\nresolution = 0\n");
        assert!(e.contains("map.resolution"), "{e}");
        let e = err("[follow]\ncontroller = \"lqr\"\n");
        assert!(e.contains("lqr") && e.contains("line 2"), "{e}");
        let ok = Config::parse("[follow]\ncontroller = \"pure_pursuit\"\n", path).unwrap();
        assert_eq!(ok.follow.controller.name(), "pure_pursuit");
    }
}
