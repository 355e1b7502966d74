//! Estimating where the robot is: wheel odometry, EKF-SLAM on marker landmarks, and
//! Monte-Carlo localisation with the lidar on a known map, and lidar SLAM (scan matching
//! and a pose graph) for places without markers.

pub mod config;
mod downdate;
pub mod ekf;
pub mod ellipse;
pub mod lidar;
pub mod mcl;
pub mod motion;
pub mod odometry;
