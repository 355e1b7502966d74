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
use crate::slam::mcl::config::LocalizationConfig;
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
    #[error("config {path}{}: field `{field}` = {value}: {reason}", line.map(|l| format!(":{l}")).unwrap_or_default())]
    Invalid {
        path: PathBuf,
        /// The line that sets the field, when the file sets it.
        line: Option<usize>,
        field: String,
        value: String,
        reason: std::borrow::Cow<'static, str>,
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
    /// Which estimator places the robot; Monte-Carlo localisation's settings.
    pub localization: LocalizationConfig,
    /// Lidar SLAM's matching, keyframes and loop closure (`--estimator slam`).
    pub lidar_slam: crate::slam::lidar::LidarSlamConfig,
    /// `--link ros2`: topics, QoS, message variants.
    pub ros2: crate::link::ros2::config::Ros2Config,
    pub serial: SerialConfig,
    pub vision: VisionConfig,
    /// The arm on the robot, its kinematics and limits. No [arm], no arm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub arm: Option<crate::arm::config::ArmConfig>,
    /// `--record`: what a recording holds, and a folder to record every session into.
    pub record: crate::record::RecordConfig,
    /// The collision monitor's zones around the robot and its data's age limit.
    pub safety: crate::control::collision_monitor::SafetyConfig,
    /// Lane mode: the lane camera, its pipeline and lane following.
    pub lane: crate::control::lane::LaneConfig,
    /// `[[fleet]]`: the robots one console drives (none: the one robot of the command
    /// line).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub fleet: Vec<crate::fleet::config::FleetEntry>,
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
            localization: self.localization.clone(),
            lidar_slam: self.lidar_slam.clone(),
            arm: self.arm.clone(),
            safety: self.safety.clone(),
            lane: self.lane.drive.clone(),
        }
    }

    /// Reads and validates a config file.
    pub fn load(path: &Path) -> Result<Config, ConfigError> {
        let text = crate::data::files::read_text_limited(path, crate::data::files::TEXT_LIMIT)
            .map_err(|source| ConfigError::Read {
                path: path.to_path_buf(),
                error: source,
            })?;
        Self::parse(&text, path)
    }

    /// Parses config text; `path` only names the source in errors.
    pub fn parse(text: &str, path: &Path) -> Result<Config, ConfigError> {
        let refused = |mut e: toml::de::Error| {
            e.set_input(Some(text));
            ConfigError::Parse {
                path: path.to_path_buf(),
                message: crate::data::number::shorten_long_numbers(e.to_string().trim_end()),
            }
        };
        let doc = toml::de::DeTable::parse(text).map_err(refused)?;
        // `[localization]` is flat in the file and grouped in memory, which serde alone
        // cannot check key by key.
        if let Some(section) = doc.get_ref().get("localization") {
            LocalizationConfig::check_section(section).map_err(refused)?;
        }
        let config = Config::deserialize(toml::de::Deserializer::from(doc)).map_err(refused)?;
        config.check_sections(path, Some(text))?;
        Ok(config)
    }

    /// Checks values a parser cannot, section by section: each section's `validate()`
    /// names its first bad field, and the error adds the file and the section.
    pub fn validate(&self, path: &Path) -> Result<(), ConfigError> {
        self.check_sections(path, None)
    }

    /// `validate`, naming the line of `text` (the file's TOML) that sets a bad field.
    fn check_sections(&self, path: &Path, text: Option<&str>) -> Result<(), ConfigError> {
        let sections = [
            ("robot", self.robot.validate()),
            ("teleop", self.teleop.validate()),
            ("slam", self.slam.validate()),
            ("race", self.race.validate()),
            ("sim", self.sim.validate()),
            ("map", self.map.validate()),
            ("plan", self.plan.validate()),
            ("follow", self.follow.validate()),
            ("lane", self.lane.validate()),
            ("mission", self.mission.validate()),
            ("localization", self.localization.validate()),
            ("lidar_slam", self.lidar_slam.validate()),
            ("ros2", self.ros2.validate()),
            ("serial", self.serial.validate()),
            ("vision", self.vision.validate()),
            ("arm", self.arm.as_ref().map_or(Ok(()), |a| a.validate())),
            ("record", self.record.validate()),
            ("safety", self.safety.validate()),
        ];
        let namespace = &self.ros2.namespace;
        if let Some(why) = crate::link::ros2::config::namespace_problem(namespace) {
            return Err(ConfigError::Invalid {
                path: path.to_path_buf(),
                line: text.and_then(|t| line_of(t, "ros2.namespace")),
                field: "ros2.namespace".into(),
                value: crate::link::ros2::config::shown_namespace(namespace),
                reason: format!("not a ROS 2 namespace: it {why}").into(),
            });
        }
        for (section, result) in sections {
            if let Err((field, value, reason)) = result {
                let field = format!("{section}.{field}");
                return Err(ConfigError::Invalid {
                    path: path.to_path_buf(),
                    line: text.and_then(|t| line_of(t, &field)),
                    field,
                    value: crate::data::number::short(value),
                    reason,
                });
            }
        }
        if let Some((field, value, reason)) = crate::fleet::config::problem(&self.fleet) {
            return Err(ConfigError::Invalid {
                path: path.to_path_buf(),
                line: text.and_then(|t| line_of(t, &field)),
                field,
                value,
                reason: reason.into(),
            });
        }
        if let Some((field, name, reason)) = self.safety.name_problem() {
            let field = format!("safety.{field}");
            return Err(ConfigError::Invalid {
                path: path.to_path_buf(),
                line: text.and_then(|t| line_of(t, &field)),
                field,
                value: format!("{name:?}"),
                reason: reason.into(),
            });
        }
        Ok(())
    }
}

/// The line (from 1) of TOML `text` that sets the dotted `field` ("sim.camera.min_range";
/// an index such as "[0]" is dropped), looked for under its table header or as a dotted
/// key under a parent table. A field of an array of tables ("safety.polygons[1].radius")
/// is looked for in that table's second `[[safety.polygons]]`.
fn line_of(text: &str, field: &str) -> Option<usize> {
    if let Some(line) = line_in_array_of_tables(text, field) {
        return Some(line);
    }
    let field = field.split('[').next().unwrap_or(field);
    let mut table = String::new();
    for (n, line) in text.lines().enumerate() {
        let line = line.trim();
        if let Some(header) = line.strip_prefix('[') {
            table = header.trim_end_matches(']').trim().to_string();
            continue;
        }
        let Some((key, _)) = line.split_once('=') else {
            continue;
        };
        let key: String = key
            .split('.')
            .map(|k| k.trim().trim_matches('"'))
            .collect::<Vec<_>>()
            .join(".");
        let full = if table.is_empty() {
            key
        } else {
            format!("{table}.{key}")
        };
        if full == field {
            return Some(n + 1);
        }
    }
    None
}

/// The line of "table[k].key" in the k-th (from 0) `[[table]]` of `text`, or that
/// header's line when the table does not set `key`; `None` for other fields.
fn line_in_array_of_tables(text: &str, field: &str) -> Option<usize> {
    let (table, rest) = field.split_once('[')?;
    let (index, key) = rest.split_once("].")?;
    let index: usize = index.parse().ok()?;
    let header = format!("[[{table}]]");
    let (mut seen, mut start) = (0, None);
    for (n, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or_default().trim();
        // A table header, not a row of a multi-line array such as `[0.4, 0.2],`.
        let names = line.trim_start_matches('[');
        if line.starts_with('[') && names.starts_with(|c: char| c.is_alphabetic() || c == '"') {
            if start.is_some() {
                break;
            }
            if line == header {
                seen += 1;
                start = (seen == index + 1).then_some(n + 1);
            }
            continue;
        }
        let sets_key = line
            .split_once('=')
            .is_some_and(|(k, _)| k.trim().trim_matches('"') == key);
        if start.is_some() && sets_key {
            return Some(n + 1);
        }
    }
    start
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
    fn every_section_names_its_bad_field_the_same_way() {
        let cases = [
            ("[robot]\ncontrol_period = 0.0", "robot.control_period", "0"),
            ("[teleop]\nspeed_step = 0.9", "teleop.speed_step", "0.9"),
            ("[race]\ncorrect_every = 0", "race.correct_every", "0"),
            ("[slam]\ngate_chi2 = -1.0", "slam.gate_chi2", "-1"),
            ("[sim.camera]\nfov_deg = 400.0", "sim.camera.fov_deg", "400"),
            (
                "[sim.encoders]\nslip_probability = 1.5",
                "sim.encoders.slip_probability",
                "1.5",
            ),
            ("[sim.lidar]\nbeams = 0", "sim.lidar.beams", "0"),
            ("[map]\nresolution = -0.05", "map.resolution", "-0.05"),
            ("[slam]\nmotor_std_deg = nan", "slam.motor_std_deg", "NaN"),
            (
                "[robot]\ncontrol_period = 1e-300",
                "robot.control_period",
                "1e-300",
            ),
            ("[robot]\ntrack = 1e308", "robot.track", "1e308"),
            ("[record]\nlevel = 0", "record.level", "0"),
            (
                "[localization]\nmax_beams = 0",
                "localization.max_beams",
                "0",
            ),
            (
                "[localization]\nconverged_std = 0",
                "localization.converged_std",
                "0",
            ),
            (
                "[localization]\nalpha_fast = 0.0005",
                "localization.alpha_fast",
                "0.0005",
            ),
            (
                "[safety]\nsource_timeout = 0.0",
                "safety.source_timeout",
                "0",
            ),
        ];
        for (text, field, value) in cases {
            let err = Config::parse(text, Path::new("bad.toml"))
                .unwrap_err()
                .to_string();
            // The line that sets it, too.
            let expected = format!("config bad.toml:2: field `{field}` = {value}:");
            assert!(err.starts_with(&expected), "{text}: {err}");
        }
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

    #[test]
    fn a_bad_safety_zone_is_named_with_its_value_and_line() {
        let path = Path::new("safety.toml");
        let err = |text: &str| Config::parse(text, path).unwrap_err().to_string();
        let zones = "[safety]\nsource_timeout = 0.4\n\n\
            [[safety.polygons]]\nname = \"stop\"\naction_type = \"stop\"\nradius = 0.15\n\n\
            [[safety.polygons]]\nname = \"slow\"\naction_type = \"slowdown\"\n";
        let e = err(&format!("{zones}radius = 0.4\nslowdown_ratio = 1.5\n"));
        assert!(
            e.starts_with(
                "config safety.toml:13: field `safety.polygons[1].slowdown_ratio` = 1.5:"
            ),
            "{e}"
        );
        let e = err(&format!(
            "{zones}points = [[0.0, 0.0], [0.4, 0.4], [0.4, 0.0], [0.0, 0.4]]\n"
        ));
        assert!(
            e.starts_with("config safety.toml:12: field `safety.polygons[1].points` = 4:"),
            "{e}"
        );
        assert!(e.contains("cross"), "{e}");
        let e = err(&format!(
            "{zones}points = [\n  [0.3, 0.2],\n  [0.3, -0.2],\n  [30.0, 0.0],\n]\n"
        ));
        assert!(
            e.starts_with("config safety.toml:12: field `safety.polygons[1].points` = 30:"),
            "{e}"
        );
        let e = err(&zones.replace("\"slow\"", "\"stop\""));
        assert!(
            e.starts_with("config safety.toml:10: field `safety.polygons[1].name` = \"stop\":"),
            "{e}"
        );
        let e = err("[[safety.polygons]]\nname = \"x\"\naction_type = \"brake\"\n");
        assert!(e.contains("brake"), "{e}");
        let ok = Config::parse(&format!("{zones}radius = 0.4\n"), path).unwrap();
        assert_eq!(ok.safety.polygons.len(), 2);
        assert_eq!(ok.safety.polygons[1].slowdown_ratio, 0.5);
        assert_eq!(ok.safety.polygons[1].min_points, 4);
    }

    #[test]
    fn a_flat_localization_section_sets_every_group() {
        let text = "[localization]\nestimator = \"mcl\"\nalpha1 = 0.3\nmax_particles = 3000\n\
            model = \"beam\"\nz_hit = 0.7\nupdate_min_d = 0.2\nalpha_slow = 0.002\n\
            initial_std_deg = 5.0\nconverged_std = 0.3\n";
        let l = Config::parse(text, Path::new("legacy.toml"))
            .unwrap()
            .localization;
        assert_eq!(l.estimator, crate::slam::mcl::config::Estimator::Mcl);
        assert_eq!(l.motion.alpha1, 0.3);
        assert_eq!(l.particles.max_particles, 3000);
        assert_eq!(
            l.measurement.model,
            crate::slam::mcl::config::SensorModel::Beam
        );
        assert_eq!(l.measurement.z_hit, 0.7);
        assert_eq!(l.schedule.update_min_d, 0.2);
        assert_eq!(l.recovery.alpha_slow, 0.002);
        assert_eq!(l.spread.initial_std_deg, 5.0);
        assert_eq!(l.spread.converged_std, 0.3);
        // What the file leaves out keeps its default, in the same groups.
        let d = LocalizationConfig::default();
        assert_eq!(l.motion.alpha2, d.motion.alpha2);
        assert_eq!(l.particles.min_particles, d.particles.min_particles);
        assert_eq!(l.spread.initial_std, d.spread.initial_std);
    }

    #[test]
    fn an_unknown_localization_key_is_named_with_its_line() {
        let parse = |text: &str| Config::parse(text, Path::new("typo.toml"));
        for text in [
            "[localization]\nalpha1 = 0.3\nalpha5 = 1\n",
            "localization.alpha1 = 0.3\n\nlocalization.alpha5 = 1\n",
        ] {
            let e = parse(text).unwrap_err().to_string();
            assert!(
                e.starts_with("config typo.toml: TOML parse error at line 3"),
                "{text}: {e}"
            );
            assert!(e.contains("unknown field `alpha5`"), "{text}: {e}");
        }
        // A value of the wrong kind, too, at its own line rather than the section's.
        let e = parse("[localization]\nalpha1 = 0.3\nmax_particles = -3\n")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("line 3") && e.contains("max_particles = -3"),
            "{e}"
        );
    }

    #[test]
    fn the_default_config_reads_back_as_written() {
        let text = toml::to_string(&Config::default()).unwrap();
        let back = Config::parse(&text, Path::new("written.toml")).unwrap();
        assert_eq!(back, Config::default());
        assert!(text.contains("[[safety.polygons]]"), "{text}");
    }
}
