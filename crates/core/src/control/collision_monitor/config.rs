//! `[safety]`: the collision monitor's zones around the robot and how old its obstacle
//! data may be. Names, meanings and most defaults follow Nav2's collision monitor (its
//! "Collision Monitor Node" configuration guide, Jazzy); where navdeck differs, the field
//! says so. The defaults are sized for a TurtleBot3 Burger.
//!
//! ```toml
//! [safety]
//! source_timeout = 0.5
//!
//! [[safety.polygons]]
//! name = "stop"
//! action_type = "stop"
//! radius = 0.15
//! ```

use serde::{Deserialize, Serialize};

/// What a zone does to the command when enough obstacle points lie in it (Nav2's
/// `action_type`: `stop`, `slowdown`, `limit`, `approach`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ActionType {
    /// No motion towards the points inside.
    Stop,
    /// Motion towards the points inside at `slowdown_ratio` of the command.
    Slowdown,
    /// Speeds capped at `linear_limit` and `angular_limit` while points are inside.
    Limit,
    /// The command scaled so that a predicted contact with the shape (the footprint unless
    /// given) stays `time_before_collision` away.
    Approach,
}

impl ActionType {
    /// The config name, as Nav2 spells it.
    pub fn name(self) -> &'static str {
        match self {
            ActionType::Stop => "stop",
            ActionType::Slowdown => "slowdown",
            ActionType::Limit => "limit",
            ActionType::Approach => "approach",
        }
    }
}

/// One zone around the robot, in the robot's frame (x forward, y left, metres). Its shape
/// is `points` (a simple polygon) or `radius` (a circle on the robot's centre); with
/// neither it is the robot's footprint, a circle of `[robot].footprint_radius` (Nav2's
/// approach zones follow the published footprint the same way).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PolygonConfig {
    /// Shown when the zone acts ("stopping ... in `stop`").
    pub name: String,
    pub action_type: ActionType,
    /// Vertices in order, `[[x, y], ...]`, at least 3 (Nav2's `points`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub points: Option<Vec<[f64; 2]>>,
    /// A circle's radius (Nav2's `circle` type).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius: Option<f64>,
    /// Obstacle points needed inside before the zone acts (Nav2 Jazzy `min_points`,
    /// default 4; Humble's `max_points` 3 meant the same, one below).
    #[serde(default = "default_min_points")]
    pub min_points: u32,
    /// A disabled zone is kept but never acts (Nav2 `enabled`, default true).
    #[serde(default = "enabled")]
    pub enabled: bool,
    /// `slowdown`: the share of the command kept (Nav2 `slowdown_ratio`, default 0.5).
    #[serde(default = "default_slowdown_ratio")]
    pub slowdown_ratio: f64,
    /// `limit`: the greatest speeds let through, m/s and rad/s (Nav2 `linear_limit` and
    /// `angular_limit`, default 0.5 each).
    #[serde(default = "default_limit")]
    pub linear_limit: f64,
    #[serde(default = "default_limit")]
    pub angular_limit: f64,
    /// `approach`: how far ahead a contact is predicted, and the command scaled so it
    /// stays this far away, s (Nav2 `time_before_collision`, default 2.0).
    #[serde(default = "default_time_before_collision")]
    pub time_before_collision: f64,
    /// `approach`: the prediction's time step, s (Nav2 `simulation_time_step`, default 0.1).
    #[serde(default = "default_simulation_time_step")]
    pub simulation_time_step: f64,
}

fn default_min_points() -> u32 {
    4
}

fn enabled() -> bool {
    true
}

fn default_slowdown_ratio() -> f64 {
    0.5
}

fn default_limit() -> f64 {
    0.5
}

fn default_time_before_collision() -> f64 {
    2.0
}

fn default_simulation_time_step() -> f64 {
    0.1
}

impl PolygonConfig {
    /// A zone of `action_type` named `name` with Nav2's defaults and no shape of its own
    /// (the footprint); set `points` or `radius` to give it one.
    pub fn new(name: &str, action_type: ActionType) -> Self {
        Self {
            name: name.to_string(),
            action_type,
            points: None,
            radius: None,
            min_points: default_min_points(),
            enabled: true,
            slowdown_ratio: default_slowdown_ratio(),
            linear_limit: default_limit(),
            angular_limit: default_limit(),
            time_before_collision: default_time_before_collision(),
            simulation_time_step: default_simulation_time_step(),
        }
    }

    /// This zone as a circle of `radius` on the robot's centre.
    pub fn circle(self, radius: f64) -> Self {
        Self {
            radius: Some(radius),
            points: None,
            ..self
        }
    }

    /// This zone as the polygon of `points`.
    pub fn polygon(self, points: &[[f64; 2]]) -> Self {
        Self {
            points: Some(points.to_vec()),
            radius: None,
            ..self
        }
    }
}

/// The `[safety]` section.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SafetyConfig {
    /// Obstacle data older than this is no data, s (Nav2 `source_timeout`, default 2.0).
    /// navdeck's 0.5 s is two and a half turns of a TurtleBot3's 5 Hz LDS-01, and 11 cm
    /// driven blind at the Burger's 0.22 m/s, where 2 s would be 44 cm, beyond every zone.
    pub source_timeout: f64,
    /// With no data or data too old, send no motion at all; false checks nothing until
    /// data comes again. Nav2 always stops and turns the check off with `source_timeout`
    /// 0; navdeck keeps the switch apart, as the `block_if_invalid` first proposed for
    /// Nav2's watchdog (its pull request 3880) did.
    pub block_if_invalid: bool,
    /// The zones, in the order they are checked; the most restrictive acting one wins.
    pub polygons: Vec<PolygonConfig>,
    /// `[safety.health]`: when a sensor counts as lost, and the lidar-lost safety mode.
    pub health: crate::health::HealthConfig,
}

impl Default for SafetyConfig {
    fn default() -> Self {
        Self {
            source_timeout: 0.5,
            block_if_invalid: true,
            polygons: default_polygons(),
            health: crate::health::HealthConfig::default(),
        }
    }
}

/// A TurtleBot3 Burger's zones. turtlebot3_navigation gives the Burger a `robot_radius`
/// of 0.105 m, and it drives at 0.22 m/s at most (seed 004's `v_max`).
fn default_polygons() -> Vec<PolygonConfig> {
    vec![
        // 4.5 cm clear of the footprint all round (a 10 Hz tick at 0.22 m/s is 2.2 cm),
        // and beyond the LDS-01's 0.12 m least range: a wall it holds the robot at stays
        // in the scan.
        PolygonConfig::new("stop", ActionType::Stop).circle(0.15),
        // Half speed with something within 0.5 m ahead, 15 cm either side of the
        // centre line (the Burger is 0.178 m wide); Nav2's default ratio. Off unless
        // switched on (`enabled = true`), as Nav2's bringup lists only its footprint
        // approach: on, it made the warehouse mission's median 7 % slower.
        PolygonConfig {
            enabled: false,
            ..PolygonConfig::new("slowdown", ActionType::Slowdown).polygon(&[
                [0.5, 0.15],
                [0.5, -0.15],
                [0.0, -0.15],
                [0.0, 0.15],
            ])
        },
        // Contact with the footprint kept 2 s away (Nav2's default), predicted every
        // 0.02 s as Nav2's footprint-approach example does: 4.4 mm at 0.22 m/s.
        PolygonConfig {
            simulation_time_step: 0.02,
            ..PolygonConfig::new("approach", ActionType::Approach)
        },
    ]
}
