//! The `ros2msg` schemas a recording carries: each type's definition followed by every
//! type it uses, separated as the MCAP ROS 2 profile asks (a line of 80 `=`, then
//! `MSG: package/Type`), so readers decode without a ROS installation.

/// One message definition and the types its fields name.
struct Definition {
    name: &'static str,
    text: &'static str,
    uses: &'static [&'static str],
}

const HEADER: &[&str] = &["std_msgs/Header"];

const DEFINITIONS: &[Definition] = &[
    Definition {
        name: "builtin_interfaces/Time",
        text: "int32 sec\nuint32 nanosec\n",
        uses: &[],
    },
    Definition {
        name: "builtin_interfaces/Duration",
        text: "int32 sec\nuint32 nanosec\n",
        uses: &[],
    },
    Definition {
        name: "std_msgs/Header",
        text: "builtin_interfaces/Time stamp\nstring frame_id\n",
        uses: &["builtin_interfaces/Time"],
    },
    Definition {
        name: "std_msgs/String",
        text: "string data\n",
        uses: &[],
    },
    Definition {
        name: "std_msgs/ColorRGBA",
        text: "float32 r\nfloat32 g\nfloat32 b\nfloat32 a\n",
        uses: &[],
    },
    Definition {
        name: "geometry_msgs/Vector3",
        text: "float64 x\nfloat64 y\nfloat64 z\n",
        uses: &[],
    },
    Definition {
        name: "geometry_msgs/Point",
        text: "float64 x\nfloat64 y\nfloat64 z\n",
        uses: &[],
    },
    Definition {
        name: "geometry_msgs/Quaternion",
        text: "float64 x\nfloat64 y\nfloat64 z\nfloat64 w\n",
        uses: &[],
    },
    Definition {
        name: "geometry_msgs/Pose",
        text: "geometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n",
        uses: &["geometry_msgs/Point", "geometry_msgs/Quaternion"],
    },
    Definition {
        name: "geometry_msgs/PoseStamped",
        text: "std_msgs/Header header\ngeometry_msgs/Pose pose\n",
        uses: &["std_msgs/Header", "geometry_msgs/Pose"],
    },
    Definition {
        name: "geometry_msgs/PoseWithCovariance",
        text: "geometry_msgs/Pose pose\nfloat64[36] covariance\n",
        uses: &["geometry_msgs/Pose"],
    },
    Definition {
        name: "geometry_msgs/PoseWithCovarianceStamped",
        text: "std_msgs/Header header\ngeometry_msgs/PoseWithCovariance pose\n",
        uses: &["std_msgs/Header", "geometry_msgs/PoseWithCovariance"],
    },
    Definition {
        name: "geometry_msgs/Twist",
        text: "geometry_msgs/Vector3 linear\ngeometry_msgs/Vector3 angular\n",
        uses: &["geometry_msgs/Vector3"],
    },
    Definition {
        name: "geometry_msgs/TwistWithCovariance",
        text: "geometry_msgs/Twist twist\nfloat64[36] covariance\n",
        uses: &["geometry_msgs/Twist"],
    },
    Definition {
        name: "geometry_msgs/Transform",
        text: "geometry_msgs/Vector3 translation\ngeometry_msgs/Quaternion rotation\n",
        uses: &["geometry_msgs/Vector3", "geometry_msgs/Quaternion"],
    },
    Definition {
        name: "geometry_msgs/TransformStamped",
        text: "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/Transform transform\n",
        uses: &["std_msgs/Header", "geometry_msgs/Transform"],
    },
    Definition {
        name: "tf2_msgs/TFMessage",
        text: "geometry_msgs/TransformStamped[] transforms\n",
        uses: &["geometry_msgs/TransformStamped"],
    },
    Definition {
        name: "nav_msgs/Odometry",
        text: "std_msgs/Header header\nstring child_frame_id\n\
               geometry_msgs/PoseWithCovariance pose\ngeometry_msgs/TwistWithCovariance twist\n",
        uses: &[
            "std_msgs/Header",
            "geometry_msgs/PoseWithCovariance",
            "geometry_msgs/TwistWithCovariance",
        ],
    },
    Definition {
        name: "nav_msgs/MapMetaData",
        text: "builtin_interfaces/Time map_load_time\nfloat32 resolution\nuint32 width\n\
               uint32 height\ngeometry_msgs/Pose origin\n",
        uses: &["builtin_interfaces/Time", "geometry_msgs/Pose"],
    },
    Definition {
        name: "nav_msgs/OccupancyGrid",
        text: "std_msgs/Header header\nnav_msgs/MapMetaData info\nint8[] data\n",
        uses: &["std_msgs/Header", "nav_msgs/MapMetaData"],
    },
    Definition {
        name: "nav_msgs/Path",
        text: "std_msgs/Header header\ngeometry_msgs/PoseStamped[] poses\n",
        uses: &["std_msgs/Header", "geometry_msgs/PoseStamped"],
    },
    Definition {
        name: "sensor_msgs/JointState",
        text: "std_msgs/Header header\nstring[] name\nfloat64[] position\nfloat64[] velocity\n\
               float64[] effort\n",
        uses: HEADER,
    },
    Definition {
        name: "sensor_msgs/LaserScan",
        text: "std_msgs/Header header\nfloat32 angle_min\nfloat32 angle_max\n\
               float32 angle_increment\nfloat32 time_increment\nfloat32 scan_time\n\
               float32 range_min\nfloat32 range_max\nfloat32[] ranges\nfloat32[] intensities\n",
        uses: HEADER,
    },
    Definition {
        name: "sensor_msgs/Image",
        text: "std_msgs/Header header\nuint32 height\nuint32 width\nstring encoding\n\
               uint8 is_bigendian\nuint32 step\nuint8[] data\n",
        uses: HEADER,
    },
    Definition {
        name: "visualization_msgs/Marker",
        text: "int32 ARROW=0\nint32 CUBE=1\nint32 SPHERE=2\nint32 CYLINDER=3\n\
               int32 LINE_STRIP=4\nint32 LINE_LIST=5\nint32 CUBE_LIST=6\nint32 SPHERE_LIST=7\n\
               int32 POINTS=8\nint32 TEXT_VIEW_FACING=9\nint32 MESH_RESOURCE=10\n\
               int32 TRIANGLE_LIST=11\nint32 ADD=0\nint32 MODIFY=0\nint32 DELETE=2\n\
               int32 DELETEALL=3\n\
               std_msgs/Header header\nstring ns\nint32 id\nint32 type\nint32 action\n\
               geometry_msgs/Pose pose\ngeometry_msgs/Vector3 scale\nstd_msgs/ColorRGBA color\n\
               builtin_interfaces/Duration lifetime\nbool frame_locked\n\
               geometry_msgs/Point[] points\nstd_msgs/ColorRGBA[] colors\nstring text\n\
               string mesh_resource\nbool mesh_use_embedded_materials\n",
        uses: &[
            "std_msgs/Header",
            "geometry_msgs/Pose",
            "geometry_msgs/Vector3",
            "std_msgs/ColorRGBA",
            "builtin_interfaces/Duration",
            "geometry_msgs/Point",
        ],
    },
    Definition {
        name: "visualization_msgs/MarkerArray",
        text: "visualization_msgs/Marker[] markers\n",
        uses: &["visualization_msgs/Marker"],
    },
    Definition {
        name: "rcl_interfaces/Log",
        text: "byte DEBUG=10\nbyte INFO=20\nbyte WARN=30\nbyte ERROR=40\nbyte FATAL=50\n\
               builtin_interfaces/Time stamp\nuint8 level\nstring name\nstring msg\n\
               string file\nstring function\nuint32 line\n",
        uses: &["builtin_interfaces/Time"],
    },
    Definition {
        name: "navdeck_msgs/MarkerSighting",
        text: "# One ArUco marker seen by the robot's camera, in the robot frame.\n\
               uint32 id\n\
               float64 range    # metres from the robot centre\n\
               float64 bearing  # radians from the heading, counter-clockwise positive\n",
        uses: &[],
    },
    Definition {
        name: "navdeck_msgs/MarkerSightings",
        text: "# The markers one camera frame showed, as the estimator received them.\n\
               std_msgs/Header header\nnavdeck_msgs/MarkerSighting[] sightings\n",
        uses: &["std_msgs/Header", "navdeck_msgs/MarkerSighting"],
    },
    Definition {
        name: "navdeck_msgs/SensorFrame",
        text: "# One poll of the robot's link, exactly as navdeck's pilot received it:\n\
               # a replay feeds these back to re-run the estimator bit for bit.\n\
               float64 time             # session time of the poll, seconds\n\
               bool failed              # the poll failed; `failure` says why\n\
               string failure\n\
               float64 stamp            # link time of the newest data, seconds\n\
               float64 elapsed          # seconds of motion the wheel travel covers\n\
               bool has_wheels\n\
               float64 wheel_left       # metres travelled since the previous frame\n\
               float64 wheel_right\n\
               bool has_sightings\n\
               navdeck_msgs/MarkerSighting[] sightings\n\
               bool has_scan\n\
               float64 scan_angle_min   # radians\n\
               float64 scan_angle_increment\n\
               float64 scan_range_min   # metres\n\
               float64 scan_range_max\n\
               float32[] scan_ranges    # +inf where a beam hit nothing\n\
               uint8 gripper            # 0 none, 1 open, 2 opening, 3 closing, 4 closed, 5 holding\n\
               bool has_initial_pose\n\
               float64[3] initial_pose  # x, y (m), theta (rad) in the map frame\n\
               bool has_arm\n\
               float64[4] arm_joints    # radians\n\
               bool has_camera\n\
               uint32[] camera_ids      # every marker ID the camera decoded\n\
               uint32 camera_accepted\n\
               uint32 camera_rejected\n\
               float64 camera_latency   # seconds; negative when not timed\n\
               string camera_error\n\
               bool has_goal\n\
               float64[3] goal          # x, y (m), theta (rad) in the map frame: a goal pose\n",
        uses: &["navdeck_msgs/MarkerSighting"],
    },
    Definition {
        name: "navdeck_msgs/Input",
        text: "# One thing the console was told: time passing, a key, a new terminal size.\n\
               uint8 UPDATE=0\nuint8 KEY=1\nuint8 RESIZE=2\n\
               uint8 kind\n\
               float64 time       # session time, seconds\n\
               string key         # as keymaps name it, e.g. \"w\", \"space\", \"ctrl-c\"\n\
               uint8 key_event    # 0 press, 1 repeat, 2 release\n\
               uint16 width       # terminal columns and rows (RESIZE)\n\
               uint16 height\n",
        uses: &[],
    },
    Definition {
        name: "navdeck_msgs/Block",
        text: "uint32 marker_a\nuint32 marker_b\nfloat64 x\nfloat64 y\nfloat64 theta\nbool held\n",
        uses: &[],
    },
    Definition {
        name: "navdeck_msgs/Truth",
        text: "# The digital twin's ground truth after a poll (for scoring; never decided with).\n\
               float64 time\nfloat64 x\nfloat64 y\nfloat64 theta\n\
               float64 linear           # true twist, m/s and rad/s\nfloat64 angular\n\
               float64 command_linear   # the twist the twin was last told\n\
               float64 command_angular\n\
               float64 distance_driven  # metres\nuint32 collisions\n\
               navdeck_msgs/Block[] blocks  # empty when no block moved since the last message\n",
        uses: &["navdeck_msgs/Block"],
    },
];

fn find(name: &str) -> Option<&'static Definition> {
    DEFINITIONS.iter().find(|d| d.name == name)
}

/// `pkg/msg/Type` (as ROS 2 tools name a type) as `pkg/Type` (as definitions refer to it).
pub fn short_name(name: &str) -> String {
    name.replacen("/msg/", "/", 1)
}

/// The full `ros2msg` schema text of `name` (either form), or None for a type not here.
pub fn schema(name: &str) -> Option<String> {
    let name = short_name(name);
    let name = name.as_str();
    let top = find(name)?;
    let mut out = top.text.to_string();
    let mut done = vec![name];
    let mut queue: Vec<&str> = top.uses.to_vec();
    while let Some(next) = queue.first().copied() {
        queue.remove(0);
        if done.contains(&next) {
            continue;
        }
        done.push(next);
        let d = find(next)?;
        out += &format!("{}\nMSG: {}\n{}", "=".repeat(80), d.name, d.text);
        queue.extend(d.uses.iter().copied());
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_type_a_definition_names_is_defined() {
        for d in DEFINITIONS {
            assert!(schema(d.name).is_some(), "{}", d.name);
            for line in d.text.lines() {
                let ty = line.split_whitespace().next().unwrap_or("");
                let base = ty.split('[').next().unwrap();
                if base.contains('/') {
                    assert!(d.uses.contains(&base), "{} uses {base}", d.name);
                }
            }
        }
    }

    #[test]
    fn dependencies_follow_once_each_after_a_separator() {
        let text = schema("nav_msgs/Odometry").unwrap();
        assert!(text.starts_with("std_msgs/Header header\n"));
        assert_eq!(text.matches("MSG: std_msgs/Header\n").count(), 1);
        assert_eq!(text.matches("MSG: builtin_interfaces/Time\n").count(), 1);
        assert!(text.contains(&format!("{}\nMSG: geometry_msgs/Pose\n", "=".repeat(80))));
    }
}
