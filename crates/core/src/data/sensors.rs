//! What the robot reports: wheel travel, marker sightings, laser scans, the gripper.

use super::camera::CameraStatus;
use serde::{Deserialize, Serialize};

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

impl LaserScan {
    /// Where the beams that hit something ended, in the frame of `pose` (the robot's).
    pub fn hits(
        &self,
        pose: crate::geometry::Pose2,
    ) -> impl Iterator<Item = crate::geometry::Point2> {
        self.ranges.iter().enumerate().filter_map(move |(k, &r)| {
            let r = f64::from(r);
            // Beam k points along angle_min + k * angle_increment (sensor_msgs/LaserScan).
            let a = pose.theta + self.angle_min + k as f64 * self.angle_increment;
            (r >= self.range_min && r <= self.range_max)
                .then(|| crate::geometry::Point2::new(pose.x + r * a.cos(), pose.y + r * a.sin()))
        })
    }
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
    pub camera: Option<CameraStatus>,
    /// A pose estimate placed from outside navdeck (RViz's "2D Pose Estimate" on ROS 2
    /// `/initialpose`), in the map frame.
    pub initial_pose: Option<crate::geometry::Pose2>,
    /// A goal given from outside navdeck (RViz's "2D Goal Pose" on ROS 2 `/goal_pose`),
    /// in the map frame: plan to it and drive there, ending facing its heading.
    pub goal: Option<crate::geometry::Pose2>,
    /// An arm's joints, when the robot has one and reported them.
    pub arm: Option<super::ArmState>,
    /// What the lane camera's pipeline made of its newest frame.
    pub lane: Option<super::LaneSighting>,
    /// The floor tags the tag camera saw in its newest frame (seed 003 §2.1), if one
    /// arrived: an empty list is a frame with none in view.
    pub tags: Option<Vec<super::TagSighting>>,
}
