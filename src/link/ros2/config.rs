//! `[ros2]`: topic names, QoS, message variants and the robot's wheels, for `--link ros2`.

use crate::data::check::Invalid;
use serde::{Deserialize, Serialize};

/// Which message cmd_vel carries (Humble's TurtleBot3 takes Twist, Jazzy's TwistStamped).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CmdVelType {
    /// Publish what the discovered subscriber reads; both until one is discovered.
    Auto,
    Twist,
    TwistStamped,
}

/// The ROS 2 distribution, where message layouts differ (visualization_msgs/Marker).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Distro {
    Humble,
    Jazzy,
}

/// Reliability of a topic's QoS.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Reliability {
    Reliable,
    BestEffort,
}

/// A topic's QoS: ROS 2's default profile is reliable, volatile, keep-last 10.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Qos {
    pub reliability: Reliability,
    pub depth: u32,
}

impl Default for Qos {
    fn default() -> Self {
        Self {
            reliability: Reliability::Reliable,
            depth: 10,
        }
    }
}

impl Qos {
    /// ROS 2's sensor-data profile: best effort, keep-last 5.
    pub const SENSOR_DATA: Qos = Qos {
        reliability: Reliability::BestEffort,
        depth: 5,
    };
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Ros2Config {
    /// Namespace put before relative topic names, e.g. "/tb3" (`--ns` overrides).
    pub namespace: String,
    pub odom_topic: String,
    pub joint_states_topic: String,
    pub scan_topic: String,
    pub cmd_vel_topic: String,
    pub cmd_vel_type: CmdVelType,
    /// The gripper's std_msgs/Float64 position command topic.
    pub gripper_topic: String,
    pub gripper_open: f64,
    pub gripper_closed: f64,
    pub map_topic: String,
    pub plan_topic: String,
    pub landmarks_topic: String,
    pub pose_topic: String,
    /// Where RViz's "2D Pose Estimate" arrives (geometry_msgs/PoseWithCovarianceStamped).
    pub initial_pose_topic: String,
    /// Where MCL's particles go out (geometry_msgs/PoseArray, best effort as AMCL's).
    pub particle_cloud_topic: String,
    pub map_frame: String,
    pub odom_frame: String,
    /// Wheel joints in /joint_states and the wheel radius, metres (TurtleBot3: 0.033).
    pub left_wheel_joint: String,
    pub right_wheel_joint: String,
    pub wheel_radius: f64,
    /// Without odometry for this long the link is lost, seconds.
    pub odom_timeout: f64,
    pub distro: Distro,
    pub qos: Qos,
    pub scan_qos: Qos,
    /// Only these local addresses (e.g. ["127.0.0.1"]); empty for every interface.
    pub interfaces: Vec<String>,
    /// How often the map and landmarks go out for RViz, Hz (pose and TF follow control).
    pub picture_rate_hz: f64,
}

impl Default for Ros2Config {
    fn default() -> Self {
        Self {
            namespace: String::new(),
            odom_topic: "odom".into(),
            joint_states_topic: "joint_states".into(),
            scan_topic: "scan".into(),
            cmd_vel_topic: "cmd_vel".into(),
            cmd_vel_type: CmdVelType::Auto,
            gripper_topic: "gripper/position".into(),
            gripper_open: 0.01,
            gripper_closed: -0.01,
            map_topic: "map".into(),
            plan_topic: "plan".into(),
            landmarks_topic: "landmarks".into(),
            pose_topic: "navdeck/pose".into(),
            initial_pose_topic: "initialpose".into(),
            particle_cloud_topic: "particlecloud".into(),
            map_frame: "map".into(),
            odom_frame: "odom".into(),
            left_wheel_joint: "wheel_left_joint".into(),
            right_wheel_joint: "wheel_right_joint".into(),
            wheel_radius: 0.033,
            odom_timeout: 0.5,
            distro: Distro::Jazzy,
            qos: Qos::default(),
            scan_qos: Qos::SENSOR_DATA,
            interfaces: Vec::new(),
            picture_rate_hz: 1.0,
        }
    }
}

impl Ros2Config {
    pub fn validate(&self) -> Result<(), Invalid> {
        crate::data::check::within(&[
            ("wheel_radius", self.wheel_radius, 0.005, 0.5),
            ("odom_timeout", self.odom_timeout, 0.01, 60.0),
            ("picture_rate_hz", self.picture_rate_hz, 0.01, 100.0),
            // Joint positions, metres or radians.
            ("gripper_open", self.gripper_open, -1000.0, 1000.0),
            ("gripper_closed", self.gripper_closed, -1000.0, 1000.0),
        ])?;
        crate::data::check::counts_within(&[
            ("qos.depth", u64::from(self.qos.depth), 1, 1000),
            ("scan_qos.depth", u64::from(self.scan_qos.depth), 1, 1000),
        ])
    }
}
