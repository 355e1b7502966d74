//! The one trait every robot connection implements (twin, ROS 2, serial, test doubles).
//! The data that crosses it lives below every other module, in `navdeck_core::data`.

#[cfg(feature = "vision")]
pub mod camera;

pub mod rate;
pub mod record;
pub mod replay;
pub mod ros2;
pub mod runtime;
pub mod serial;
pub mod sim;
#[cfg(feature = "vision")]
pub mod tag_camera;
pub mod tasks;

use nalgebra::Matrix3;
use navdeck_core::data::Level;
pub use navdeck_core::data::{
    Command, GripperCommand, GripperState, LaserScan, MarkerSighting, SensorFrame, WheelTravel,
};
use navdeck_core::geometry::{Point2, Pose2};
use navdeck_core::map::grid::OccupancyGrid;
use navdeck_core::slam::ekf::LandmarkEstimate;
pub use navdeck_msgs::tag_graph_markers::TagGraphPicture;

/// A line for the console's log from the link.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Notice {
    pub level: Level,
    pub text: String,
    /// The robot's node that said it (its /rosout); None for the link's own line.
    pub source: Option<String>,
}

impl Notice {
    pub fn info(text: impl Into<String>) -> Self {
        Self {
            level: Level::Info,
            text: text.into(),
            source: None,
        }
    }
    pub fn warn(text: impl Into<String>) -> Self {
        Self {
            level: Level::Warn,
            text: text.into(),
            source: None,
        }
    }
}

/// A line of the console's log, for a link that passes it on (/rosout over ROS 2).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ConsoleLine {
    pub level: Level,
    pub text: String,
    /// The robot's node that said it; None for navdeck's own line.
    pub source: Option<String>,
}

/// What navdeck believes, for a link that shows it to other tools (RViz over ROS 2).
/// The heavy parts are present only when due.
#[derive(Clone, Debug, Default)]
pub struct Picture {
    /// Session time, seconds.
    pub stamp: f64,
    pub pose: Pose2,
    pub pose_covariance: Matrix3<f64>,
    /// MCL's particles, when it runs (at the full picture's period).
    pub particles: Option<Vec<Pose2>>,
    pub landmarks: Option<Vec<LandmarkEstimate>>,
    pub path: Option<Vec<Point2>>,
    pub map: Option<OccupancyGrid>,
    /// The console's state as JSON (`app::mission_state`), when it changed.
    pub state: Option<String>,
    /// Route mode's tag graph and route, when a tag map is laid (at the full period).
    pub tag_graph: Option<TagGraphPicture>,
}

/// Why a link could not do what was asked.
#[derive(Debug, thiserror::Error)]
pub enum LinkError {
    #[error("link lost: {0}")]
    Lost(String),
    #[error("link I/O: {0}")]
    Io(#[from] std::io::Error),
    /// A failure read back from a recording, in the words it was recorded with.
    #[error("{0}")]
    Replayed(String),
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
    /// The twin only: carries the robot to `pose` behind its odometry's back (a kidnapped
    /// robot, for tests). False where there is no twin.
    fn teleport(&mut self, _pose: Pose2) -> bool {
        false
    }
    /// Ground truth, when a simulator stands behind this link (for display and scoring).
    fn ground_truth(&self) -> Option<&dyn navdeck_core::sim::GroundTruth> {
        None
    }
    /// The twin only: the faults injected into it (`--fault`, `:fault`), which are in
    /// force now and when each was, on the twin's time. None where there is no twin.
    fn faults(&self) -> Option<&navdeck_core::sim::Faults> {
        None
    }
    /// The twin only: its fault schedule, to add to or clear. None where there is no twin.
    fn faults_mut(&mut self) -> Option<&mut navdeck_core::sim::Faults> {
        None
    }
    /// What the link knows of its peer, for the status panel: short labels (at most
    /// seven characters) and values, e.g. the DDS domain and the rates topics arrive at.
    fn details(&self, _now: f64) -> Vec<(&'static str, String)> {
        Vec::new()
    }
    /// What the link noticed since the last call (retries, bad replies, dropped messages,
    /// a type mismatch), one line each, for the console's log.
    fn take_notes(&mut self) -> Vec<Notice> {
        Vec::new()
    }
    /// Whether the link passes the console's log on (`log`): /rosout over ROS 2.
    fn takes_log(&self) -> bool {
        false
    }
    /// The console's log lines written since the last call, oldest first.
    fn log(&mut self, _lines: &[ConsoleLine]) {}
}
