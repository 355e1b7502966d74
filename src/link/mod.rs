//! The one trait every robot connection implements (twin, ROS 2, serial, test doubles),
//! and the data that crosses it.

#[cfg(feature = "vision")]
pub mod camera;
pub mod ros2;
pub mod serial;
pub mod sim;

use crate::geometry::{Point2, Pose2, Twist};
use crate::map::grid::OccupancyGrid;
use crate::slam::ekf::LandmarkEstimate;
use nalgebra::Matrix3;
use serde::{Deserialize, Serialize};

/// What the console asks of the robot for the next control period.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Command {
    pub twist: Twist,
    /// `Some` to move the gripper; `None` leaves it as it is.
    pub gripper: Option<GripperCommand>,
}

impl Command {
    pub const STOP: Command = Command {
        twist: Twist::ZERO,
        gripper: None,
    };
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GripperCommand {
    Open,
    Close,
}

/// The gripper as the robot reports it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GripperState {
    Open,
    Opening,
    Closing,
    /// Closed on nothing.
    Closed,
    /// Closed around a block (the twin knows; a real robot may not).
    Holding,
}

impl GripperState {
    pub fn label(self) -> &'static str {
        match self {
            Self::Open => "open",
            Self::Opening => "opening",
            Self::Closing => "closing",
            Self::Closed => "closed",
            Self::Holding => "holding",
        }
    }
}

/// Travel of each wheel since the previous frame, metres (seed 001's l and r).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct WheelTravel {
    pub left: f64,
    pub right: f64,
}

/// One marker seen by the camera: seed 001's measurement (r, alpha) in the robot frame.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct MarkerSighting {
    pub id: u32,
    /// Range from the robot centre, metres.
    pub range: f64,
    /// Bearing from the robot's heading, radians, CCW positive, in (-pi, pi].
    pub bearing: f64,
}

/// A planar laser scan in the robot frame, laid out like sensor_msgs/LaserScan.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LaserScan {
    pub angle_min: f64,
    pub angle_increment: f64,
    pub range_min: f64,
    pub range_max: f64,
    /// One range per beam; `f32::INFINITY` where nothing was hit within `range_max`.
    pub ranges: Vec<f32>,
}

/// Everything the robot reported since the previous poll.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SensorFrame {
    /// Link time of the newest data, seconds.
    pub stamp: f64,
    /// Seconds of robot motion the wheel travel covers.
    pub elapsed: f64,
    pub wheels: Option<WheelTravel>,
    /// Sightings of the newest camera frame, if one arrived.
    pub sightings: Option<Vec<MarkerSighting>>,
    /// The newest scan, if one arrived.
    pub scan: Option<LaserScan>,
    pub gripper: Option<GripperState>,
    /// How the camera pipeline did on the newest frame (when frames are detected in navdeck).
    pub camera: Option<crate::perception::frame::CameraStatus>,
}

/// A line for the console's log from the link.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Notice {
    pub warning: bool,
    pub text: String,
}

impl Notice {
    pub fn info(text: impl Into<String>) -> Self {
        Self {
            warning: false,
            text: text.into(),
        }
    }
    pub fn warn(text: impl Into<String>) -> Self {
        Self {
            warning: true,
            text: text.into(),
        }
    }
}

/// What navdeck believes, for a link that shows it to other tools (RViz over ROS 2).
/// The heavy parts are present only when due.
#[derive(Clone, Debug, Default)]
pub struct Picture {
    /// Session time, seconds.
    pub stamp: f64,
    pub pose: Pose2,
    pub pose_covariance: Matrix3<f64>,
    pub landmarks: Option<Vec<LandmarkEstimate>>,
    pub path: Option<Vec<Point2>>,
    pub map: Option<OccupancyGrid>,
}

/// Why a link could not do what was asked.
#[derive(Debug, thiserror::Error)]
pub enum LinkError {
    #[error("link lost: {0}")]
    Lost(String),
    #[error("link I/O: {0}")]
    Io(#[from] std::io::Error),
}

/// A connection to one robot. Sync and `Send`; any async I/O lives inside the implementation.
///
/// Time is passed in: `poll(now)` tells the link how far the session clock has advanced,
/// which the twin uses to step its physics and real links use to judge staleness.
pub trait RobotLink: Send {
    /// Short label for the status panel, e.g. `sim:arena`.
    fn label(&self) -> String;
    /// Command to hold from now until the next `send`.
    fn send(&mut self, command: &Command) -> Result<(), LinkError>;
    /// Collects what the robot reported up to `now` (seconds on the session clock).
    fn poll(&mut self, now: f64) -> Result<SensorFrame, LinkError>;
    /// Best-effort zero velocity, used on quit, error, panic and signals.
    fn stop(&mut self);
    /// How often the link wants the full picture (map, landmarks, plan), seconds; `None`
    /// when it shows nothing (the twin).
    fn picture_period(&self) -> Option<f64> {
        None
    }
    /// Shows what navdeck believes: the pose every control step, the rest when due.
    fn show(&mut self, _picture: &Picture) {}
    /// The digital twin behind this link, when there is one (ground truth for display).
    fn twin(&self) -> Option<&crate::sim::Twin> {
        None
    }
    /// What the link noticed since the last call (retries, bad replies, dropped messages,
    /// a type mismatch), one line each, for the console's log.
    fn take_notes(&mut self) -> Vec<Notice> {
        Vec::new()
    }
    /// The digital twin behind this link, to change how it senses (e.g. its rendered camera).
    fn twin_mut(&mut self) -> Option<&mut crate::sim::Twin> {
        None
    }
}
