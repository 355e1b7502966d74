//! The arm's and the gripper's ROS 2 types (trajectory_msgs, control_msgs), laid out field
//! for field as their `.msg` and `.action` definitions (Jazzy's, unchanged since Foxy).

use crate::ros::{Duration, Header};
use serde::{Deserialize, Serialize};

/// trajectory_msgs/JointTrajectoryPoint: values in the order of the trajectory's joints.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct JointTrajectoryPoint {
    pub positions: Vec<f64>,
    pub velocities: Vec<f64>,
    pub accelerations: Vec<f64>,
    pub effort: Vec<f64>,
    pub time_from_start: Duration,
}

/// trajectory_msgs/JointTrajectory.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct JointTrajectory {
    pub header: Header,
    pub joint_names: Vec<String>,
    pub points: Vec<JointTrajectoryPoint>,
}

/// control_msgs/GripperCommand: a gap (or joint position), metres, and the effort limit.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct GripperCommand {
    pub position: f64,
    pub max_effort: f64,
}

/// control_msgs/action/GripperCommand's goal.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct GripperCommandGoal {
    pub command: GripperCommand,
}

/// control_msgs/action/GripperCommand's result.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct GripperCommandResult {
    pub position: f64,
    pub effort: f64,
    pub stalled: bool,
    pub reached_goal: bool,
}

/// control_msgs/action/GripperCommand's feedback (the result's fields).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct GripperCommandFeedback {
    pub position: f64,
    pub effort: f64,
    pub stalled: bool,
    pub reached_goal: bool,
}

// ros2-client's action client asks its goal, result and feedback types to be Messages.
impl ros2_client::Message for GripperCommandGoal {}
impl ros2_client::Message for GripperCommandResult {}
impl ros2_client::Message for GripperCommandFeedback {}
