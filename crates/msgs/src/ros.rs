//! The ROS 2 message types navdeck speaks, laid out field for field as their `.msg`
//! definitions so that CDR (the DDS wire encoding) reads and writes them as ROS 2 does.
//! One file per ROS package; every type is used from here, as `ros::Name`.

mod builtin_interfaces;
mod geometry_msgs;
mod nav_msgs;
mod rcl_interfaces;
mod sensor_msgs;
mod std_msgs;
mod tf2_msgs;
mod visualization_msgs;

pub use builtin_interfaces::{Duration, Time};
pub use geometry_msgs::{
    Covariance6, Point, Pose, PoseArray, PoseStamped, PoseWithCovariance,
    PoseWithCovarianceStamped, Quaternion, Transform, TransformStamped, Twist, TwistStamped,
    TwistWithCovariance, Vector3,
};
pub use nav_msgs::{Cells, MapMetaData, OccupancyGrid, Odometry, Path};
pub use rcl_interfaces::Log;
pub use sensor_msgs::{
    CameraInfo, CompressedImage, Image, JointState, LaserScan, RegionOfInterest,
};
pub use std_msgs::{ColorRgba, Float64, Header, StringMsg};
pub use tf2_msgs::TfMessage;
pub use visualization_msgs::{
    MARKER_ADD, MARKER_CUBE, MARKER_CUBE_LIST, MARKER_DELETEALL, MARKER_LINE_LIST,
    MARKER_LINE_STRIP, MARKER_TEXT_VIEW_FACING, MarkerArray, MarkerHumble, MarkerJazzy, MeshFile,
    UvCoordinate,
};

pub use crate::arm_msgs::{
    GripperCommand, GripperCommandFeedback, GripperCommandGoal, GripperCommandResult,
    JointTrajectory, JointTrajectoryPoint,
};
