//! `[ros2]`: topic names, QoS, message variants and the robot's wheels, for `--link ros2`.

use navdeck_core::data::check::Invalid;
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

impl Distro {
    /// The distribution navdeck was built for (cargo feature `humble` or `jazzy`).
    pub const BUILT: Distro = if cfg!(feature = "jazzy") {
        Distro::Jazzy
    } else {
        Distro::Humble
    };
}

/// How much of the robot's /rosout reaches the console's log.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RosoutLevel {
    Debug,
    Info,
    Warn,
    Error,
    /// None of it.
    Off,
}

impl RosoutLevel {
    /// The lowest rcl_interfaces/Log severity shown (above FATAL for `off`).
    pub fn lowest(self) -> u8 {
        match self {
            RosoutLevel::Debug => 10,
            RosoutLevel::Info => 20,
            RosoutLevel::Warn => 30,
            RosoutLevel::Error => 40,
            RosoutLevel::Off => u8::MAX,
        }
    }
}

/// The robot's RMW implementation, where ROS 2 services (an action's goals) differ on the
/// wire: Fast DDS (ROS 2's default) carries the request id beside the data, rmw_cyclonedds
/// in front of it (ros2-client's "Enhanced" and "Cyclone" service mappings).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Rmw {
    FastDds,
    CycloneDds,
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
    /// Where RViz's "2D Goal Pose" arrives (geometry_msgs/PoseStamped): plan and drive.
    pub goal_topic: String,
    /// Where the mission's state goes out (std_msgs/String holding JSON, latched).
    pub state_topic: String,
    /// The console's log lines go out on /rosout (rcl_interfaces/Log).
    pub rosout: bool,
    /// The robot's /rosout lines from this severity up reach the log pane.
    pub rosout_level: RosoutLevel,
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
    // A four-joint arm and its gripper, as turtlebot3_manipulation's bringup names them.
    /// The robot has an arm: targets go out as trajectories, joint_states report it and
    /// the gripper goes to `gripper_action` instead of `gripper_topic`. Off by default.
    pub arm: bool,
    /// trajectory_msgs/JointTrajectory for the arm's JointTrajectoryController.
    pub arm_trajectory_topic: String,
    /// The arm's four joints, base first, as joint_states and the controller name them.
    pub arm_joint_names: Vec<String>,
    /// The control_msgs/action/GripperCommand action of the GripperActionController.
    pub gripper_action: String,
    /// The gripper joint's positions sent as the goal's `position`, metres
    /// (OpenManipulator-X's gripper_left_joint: 0.01 open, -0.01 closed).
    pub gripper_open_width: f64,
    pub gripper_closed_width: f64,
    /// The goal's `max_effort`, newtons (a position-controlled gripper ignores it).
    pub gripper_max_effort: f64,
    /// How the robot's RMW frames the action's service requests.
    pub gripper_action_rmw: Rmw,
    /// Route mode's tag camera and tag graph topics (`[ros2.tags]`).
    pub tags: super::tag_topics::TagTopics,
}

/// `arm_joint_names[k]`, for refusals (a field name is static).
const JOINT_FIELDS: [&str; 4] = [
    "arm_joint_names[0]",
    "arm_joint_names[1]",
    "arm_joint_names[2]",
    "arm_joint_names[3]",
];

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
            goal_topic: "goal_pose".into(),
            state_topic: "navdeck/state".into(),
            rosout: true,
            rosout_level: RosoutLevel::Info,
            map_frame: "map".into(),
            odom_frame: "odom".into(),
            left_wheel_joint: "wheel_left_joint".into(),
            right_wheel_joint: "wheel_right_joint".into(),
            wheel_radius: 0.033,
            odom_timeout: 0.5,
            distro: Distro::BUILT,
            qos: Qos::default(),
            scan_qos: Qos::SENSOR_DATA,
            interfaces: Vec::new(),
            picture_rate_hz: 1.0,
            arm: false,
            arm_trajectory_topic: "arm_controller/joint_trajectory".into(),
            arm_joint_names: ["joint1", "joint2", "joint3", "joint4"]
                .map(String::from)
                .to_vec(),
            gripper_action: "gripper_controller/gripper_cmd".into(),
            gripper_open_width: 0.01,
            gripper_closed_width: -0.01,
            gripper_max_effort: 1.0,
            gripper_action_rmw: Rmw::FastDds,
            tags: super::tag_topics::TagTopics::default(),
        }
    }
}

/// Most characters of a namespace: rmw's RMW_NAMESPACE_MAX_LENGTH (a topic name's 255
/// less DDS's 8-character prefix, less 2).
pub const NAMESPACE_MAX: usize = 245;

/// Whether `ns` is a ROS 2 namespace by rcl's rules (rmw_validate_namespace): empty (the
/// root) or `/` followed by tokens of letters, digits and underscores, none starting
/// with a digit, joined by single slashes, no trailing slash, at most `NAMESPACE_MAX`
/// characters. The error names the value (cut short) and what is wrong with it.
pub fn check_namespace(ns: &str) -> Result<(), String> {
    namespace_problem(ns).map_or(Ok(()), |why| {
        Err(format!("ROS 2 namespace {} {why}", shown_namespace(ns)))
    })
}

/// `ns` quoted for a message, cut to 40 characters.
pub fn shown_namespace(ns: &str) -> String {
    let shown: String = ns.chars().take(40).collect();
    let cut = if shown.len() < ns.len() { "…" } else { "" };
    format!("{shown:?}{cut}")
}

/// What is wrong with `ns` as a namespace (see `check_namespace`), if anything.
pub fn namespace_problem(ns: &str) -> Option<String> {
    let why = if ns.is_empty() || ns == "/" {
        return None;
    } else if ns.chars().count() > NAMESPACE_MAX {
        format!(
            "is {} characters long, over ROS 2's {NAMESPACE_MAX}",
            ns.chars().count()
        )
    } else if !ns.starts_with('/') {
        "must start with `/` (e.g. /tb3)".to_string()
    } else if ns.ends_with('/') {
        "must not end with `/`".to_string()
    } else if let Some(bad) = ns
        .chars()
        .find(|c| !(c.is_ascii_alphanumeric() || *c == '_' || *c == '/'))
    {
        format!("holds {bad:?}: only letters, digits, `_` and `/` may be used")
    } else if ns.contains("//") {
        "holds `//`: tokens are joined by single slashes".to_string()
    } else if let Some(token) = ns[1..]
        .split('/')
        .find(|t| t.starts_with(|c: char| c.is_ascii_digit()))
    {
        format!("has a token `{token}` starting with a digit")
    } else {
        return None;
    };
    Some(why)
}

impl Ros2Config {
    pub fn validate(&self) -> Result<(), Invalid> {
        navdeck_core::data::check::within(&[
            ("wheel_radius", self.wheel_radius, 0.005, 0.5),
            ("odom_timeout", self.odom_timeout, 0.01, 60.0),
            ("picture_rate_hz", self.picture_rate_hz, 0.01, 100.0),
            // Joint positions, metres or radians.
            ("gripper_open", self.gripper_open, -1000.0, 1000.0),
            ("gripper_closed", self.gripper_closed, -1000.0, 1000.0),
            ("gripper_open_width", self.gripper_open_width, -1.0, 1.0),
            ("gripper_closed_width", self.gripper_closed_width, -1.0, 1.0),
            ("gripper_max_effort", self.gripper_max_effort, 0.0, 10_000.0),
        ])?;
        navdeck_core::data::check::counts_within(&[
            ("qos.depth", u64::from(self.qos.depth), 1, 1000),
            ("scan_qos.depth", u64::from(self.scan_qos.depth), 1, 1000),
        ])?;
        self.check_joint_names()
    }

    /// Four joint names, none empty or twice.
    fn check_joint_names(&self) -> Result<(), Invalid> {
        let names = &self.arm_joint_names;
        if names.len() != 4 {
            return Err((
                "arm_joint_names",
                names.len() as f64,
                "must name exactly 4 joints (the value is how many it names)".into(),
            ));
        }
        for (k, name) in names.iter().enumerate() {
            let why = if name.trim().is_empty() || name.chars().any(char::is_control) {
                "is not a joint name"
            } else if names[..k].contains(name) {
                "is named twice"
            } else {
                continue;
            };
            // The value is the joint's position in the list; the name is in the reason.
            return Err((JOINT_FIELDS[k], k as f64, format!("{name:?} {why}").into()));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn namespaces_follow_rcl_rules() {
        for good in ["", "/", "/tb3", "/fleet/robot_1", "/_x"] {
            assert_eq!(check_namespace(good), Ok(()), "{good}");
        }
        for (bad, says) in [
            ("tb3", "start with `/`"),
            ("/tb3/", "end with `/`"),
            ("/a b", "' '"),
            ("/a//b", "`//`"),
            ("/1abc", "`1abc` starting with a digit"),
            ("/ok/2x", "`2x`"),
            ("/a\u{1b}]0;x", "'\\u{1b}'"),
        ] {
            let e = check_namespace(bad).unwrap_err();
            assert!(e.contains(says), "{bad}: {e}");
        }
        let long = format!("/{}", "a".repeat(5000));
        let e = check_namespace(&long).unwrap_err();
        assert!(e.contains("5001 characters") && e.len() < 200, "{e}");
    }

    #[test]
    fn the_arm_is_off_by_default_with_turtlebot3_manipulation_names() {
        let c = Ros2Config::default();
        assert!(!c.arm);
        assert_eq!(c.arm_joint_names, ["joint1", "joint2", "joint3", "joint4"]);
        assert_eq!(c.arm_trajectory_topic, "arm_controller/joint_trajectory");
        assert_eq!(c.gripper_action, "gripper_controller/gripper_cmd");
        assert_eq!(c.validate(), Ok(()));
    }

    #[test]
    fn bad_arm_settings_are_refused_by_field() {
        let with = |names: &[&str]| Ros2Config {
            arm_joint_names: names.iter().map(|n| n.to_string()).collect(),
            ..Ros2Config::default()
        };
        let field = |c: Ros2Config| c.validate().unwrap_err();
        assert_eq!(field(with(&["a", "b", "c"])).0, "arm_joint_names");
        let twice = field(with(&["a", "b", "a", "d"]));
        assert_eq!(twice.0, "arm_joint_names[2]");
        assert!(twice.2.contains("\"a\" is named twice"), "{twice:?}");
        assert_eq!(field(with(&["a", " ", "c", "d"])).0, "arm_joint_names[1]");
        let effort = Ros2Config {
            gripper_max_effort: -1.0,
            ..Ros2Config::default()
        };
        assert_eq!(field(effort).0, "gripper_max_effort");
    }
}
