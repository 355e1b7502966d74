//! Robot, teleop and twin parameters: TOML with every field defaulted from the seed robot.
//!
//! A config file names only what it changes; an unknown field or a bad value is refused
//! with the file, line and field in the message.

use crate::control::config::FollowConfig;
pub use crate::data::robot::RobotConfig;
use crate::link::serial::config::SerialConfig;
use crate::map::config::MapConfig;
use crate::mission::config::MissionConfig;
use crate::perception::config::VisionConfig;
pub use crate::pilot::config::{RaceConfig, TeleopConfig};
use crate::plan::config::PlanConfig;
pub use crate::sim::config::{
    CameraConfig, EncoderConfig, GripperConfig, LidarConfig, PhysicsConfig, SimConfig,
};
pub use crate::slam::config::SlamConfig;
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

impl Config {
    /// The sections that decide how the robot moves, for the pilot.
    pub fn pilot_settings(&self) -> crate::pilot::config::Settings {
        crate::pilot::config::Settings {
            robot: self.robot.clone(),
            teleop: self.teleop.clone(),
            race: self.race.clone(),
            slam: self.slam.clone(),
            map: self.map.clone(),
            plan: self.plan.clone(),
            follow: self.follow.clone(),
            mission: self.mission.clone(),
        }
    }

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
