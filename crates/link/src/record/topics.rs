//! Every topic a recording holds, with its ROS 2 type.

/// One recorded topic.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Topic {
    Odometry,
    JointStates,
    Scan,
    Sightings,
    Image,
    CmdVel,
    Estimate,
    Landmarks,
    Map,
    Plan,
    Tf,
    Log,
    Input,
    Mode,
    Frame,
    Truth,
}

/// (topic, name, ROS 2 type as rosbag2 names it), in channel order: channel IDs are the
/// index plus one.
pub const TOPICS: [(Topic, &str, &str); 16] = [
    (Topic::Odometry, "/odom", "nav_msgs/msg/Odometry"),
    (
        Topic::JointStates,
        "/joint_states",
        "sensor_msgs/msg/JointState",
    ),
    (Topic::Scan, "/scan", "sensor_msgs/msg/LaserScan"),
    (
        Topic::Sightings,
        "/navdeck/sightings",
        "navdeck_msgs/msg/MarkerSightings",
    ),
    (Topic::Image, "/camera/image", "sensor_msgs/msg/Image"),
    (Topic::CmdVel, "/cmd_vel", "geometry_msgs/msg/Twist"),
    (
        Topic::Estimate,
        "/navdeck/estimate",
        "geometry_msgs/msg/PoseWithCovarianceStamped",
    ),
    (
        Topic::Landmarks,
        "/navdeck/landmarks",
        "visualization_msgs/msg/MarkerArray",
    ),
    (Topic::Map, "/map", "nav_msgs/msg/OccupancyGrid"),
    (Topic::Plan, "/plan", "nav_msgs/msg/Path"),
    (Topic::Tf, "/tf", "tf2_msgs/msg/TFMessage"),
    (Topic::Log, "/rosout", "rcl_interfaces/msg/Log"),
    (Topic::Input, "/navdeck/input", "navdeck_msgs/msg/Input"),
    (Topic::Mode, "/navdeck/mode", "std_msgs/msg/String"),
    (
        Topic::Frame,
        "/navdeck/frame",
        "navdeck_msgs/msg/SensorFrame",
    ),
    (Topic::Truth, "/navdeck/truth", "navdeck_msgs/msg/Truth"),
];

impl Topic {
    pub fn index(self) -> usize {
        TOPICS.iter().position(|(t, _, _)| *t == self).unwrap_or(0)
    }

    pub fn name(self) -> &'static str {
        TOPICS[self.index()].1
    }

    /// The topic called `name`, if a recording holds one.
    pub fn named(name: &str) -> Option<Topic> {
        TOPICS
            .iter()
            .find(|(_, n, _)| *n == name)
            .map(|(t, _, _)| *t)
    }
}
