//! What the robot perceives: marker ID conventions, camera frames and regions of them, the
//! camera's mount and intrinsics, and (feature `vision`) ArUco detection with OpenCV.

#[cfg(feature = "vision")]
pub mod aruco;
#[cfg(feature = "vision")]
mod aruco_identify;
#[cfg(feature = "vision")]
mod aruco_regions;
#[cfg(feature = "vision")]
pub mod bit_check;
pub mod blank;
#[cfg(feature = "vision")]
pub mod calibration;
pub mod colour;
#[cfg(feature = "vision")]
pub mod compressed;
pub mod config;
#[cfg(feature = "vision")]
pub mod edge_fit;
pub mod frame;
pub mod intrinsics;
pub mod lane;
pub mod lane_camera;
pub mod markers;
pub mod mount;
#[cfg(feature = "vision")]
pub mod pipeline;
pub mod region;
#[cfg(feature = "vision")]
pub mod square_pose;
pub mod tag_camera;
#[cfg(feature = "vision")]
pub mod tag_detect;
#[cfg(feature = "vision")]
pub mod tag_patterns;
#[cfg(feature = "vision")]
pub mod tag_pipeline;
