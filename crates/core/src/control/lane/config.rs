//! `[lane.drive]`: lane following's gains and speeds (seed 000 §2.4), and where it stops
//! for a light or a barrier.

use crate::data::check::Invalid;
use serde::{Deserialize, Serialize};

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LaneDriveConfig {
    /// Proportional gain on the lane error, rad/s per bird's-eye pixel (seed 000 §2.4.1:
    /// Kp = 0.0025).
    pub kp: f64,
    /// Derivative gain on the error's change from one frame to the next (seed 000 §2.4.1:
    /// Kd = 0.007).
    pub kd: f64,
    /// Top speed on a centred lane, m/s (seed 000 §2.4.2's v_max; navdeck's 0.1: at 0.15
    /// the inner line of a 0.45-0.65 m bend leaves the bird's-eye view before the PD has
    /// turned the robot, and the robot follows what is left).
    pub max_speed: f64,
    /// The speed the gains are scheduled about (seed 000 §2.4.1's nominal_speed), m/s.
    pub nominal_speed: f64,
    /// The error at which the speed law reaches zero, bird's-eye pixels (seed 000 §2.4.2's
    /// e_max; TurtleBot3's AutoRace divides by 500, half its 1000-pixel view).
    pub max_error: f64,
    /// The speed law's exponent (seed 000 §2.4.2: alpha = 2.2).
    pub alpha: f64,
    /// The curvature feed-forward's share of v kappa (seed 000 §2.4.1's Kf kappa, whose Kf
    /// the seed leaves unset): 0 steers on the PD alone, as TurtleBot3's AutoRace does; the
    /// lane's curvature fitted from one frame is noisy enough to pull the robot inside a
    /// bend.
    pub curvature_feedforward: f64,
    /// Most turn rate lane following asks for, rad/s.
    pub max_angular: f64,
    /// A red or yellow light this near (metres from the camera) stops the robot: with the
    /// post 0.6 m past its stop line and 0.35-0.45 m aside, 0.85 m stops the robot
    /// 0.15-0.2 m before the line.
    pub light_stop_range: f64,
    /// How far along the lane a light's lamps stand ahead of the camera with the robot's
    /// centre on the stop line, metres (the twin stands a light's post 0.6 m past its
    /// line, the lamps' face 2 cm before the post's centre, and the camera 5 cm before
    /// the robot's centre: 0.53): once the lamp is nearer than this and 5 cm more, the
    /// robot no longer stops for it turning.
    pub light_line_ahead: f64,
    /// A barrier down or moving this near stops the robot.
    pub barrier_stop_range: f64,
    /// Speed while passing a barrier whose opening the robot saw begin, m/s: at lane speed
    /// a robot that stopped short of the stop range (a rising arm's range reads short)
    /// needs 12 s to clear the arm, longer than the 8 s of the shortest opening the twin
    /// generates; a TurtleBot3 Burger's top speed is 0.22 m/s.
    pub crossing_speed: f64,
    /// Seconds the robot waits for an arm it remembers ahead but no frame has shown since:
    /// lowered, an arm that near would be in view, so one unseen this long stands open
    /// (or was never there: a far arm ranged short), and the robot drives on, stopping
    /// again for any arm it then sees closed.
    pub unseen_arm_patience: f64,
    /// Seconds without a lane line before lane following stops the robot.
    pub lost_after: f64,
}

impl Default for LaneDriveConfig {
    fn default() -> Self {
        Self {
            kp: 0.0025,
            kd: 0.007,
            max_speed: 0.1,
            nominal_speed: 0.1,
            max_error: 500.0,
            alpha: 2.2,
            curvature_feedforward: 0.0,
            max_angular: 2.0,
            light_stop_range: 0.85,
            light_line_ahead: 0.53,
            barrier_stop_range: 0.55,
            crossing_speed: 0.2,
            unseen_arm_patience: 30.0,
            lost_after: 1.0,
        }
    }
}

impl LaneDriveConfig {
    /// Checks signs and ranges a parser cannot.
    pub fn validate(&self) -> Result<(), Invalid> {
        crate::data::check::within(&[
            ("kp", self.kp, 0.0, 1.0),
            ("kd", self.kd, 0.0, 1.0),
            ("max_speed", self.max_speed, 0.01, 2.0),
            ("nominal_speed", self.nominal_speed, 0.01, 2.0),
            ("max_error", self.max_error, 1.0, 10_000.0),
            ("alpha", self.alpha, 0.1, 10.0),
            (
                "curvature_feedforward",
                self.curvature_feedforward,
                0.0,
                2.0,
            ),
            ("max_angular", self.max_angular, 0.01, 20.0),
            ("light_stop_range", self.light_stop_range, 0.1, 10.0),
            ("light_line_ahead", self.light_line_ahead, 0.0, 10.0),
            ("barrier_stop_range", self.barrier_stop_range, 0.1, 10.0),
            ("crossing_speed", self.crossing_speed, 0.01, 2.0),
            ("unseen_arm_patience", self.unseen_arm_patience, 1.0, 3600.0),
            ("lost_after", self.lost_after, 0.05, 60.0),
        ])
    }
}

/// `[lane]`: the lane camera (`[lane.camera]`), its pipeline's thresholds
/// (`[lane.vision]`) and lane following (`[lane.drive]`).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LaneConfig {
    pub camera: crate::perception::lane_camera::LaneCameraConfig,
    pub vision: crate::perception::lane::LaneVisionConfig,
    pub drive: LaneDriveConfig,
}

impl LaneConfig {
    /// The first bad field, named within `[lane]` (`camera.width`, `vision.glare_value`,
    /// `drive.kp`).
    pub fn validate(&self) -> Result<(), Invalid> {
        // The path within `[lane]`: made once for a refused field, as the config is read.
        let path = |part: &str, field: &str| -> &'static str {
            Box::leak(format!("{part}.{field}").into_boxed_str())
        };
        if let Some((field, value, reason)) = self.camera.invalid() {
            return Err((path("camera", field), value, reason.into()));
        }
        if let Some((field, value, reason)) = self.vision.invalid() {
            return Err((path("vision", field), value, reason.into()));
        }
        self.drive
            .validate()
            .map_err(|(field, value, reason)| (path("drive", field), value, reason))
    }
}
