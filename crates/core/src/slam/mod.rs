//! Estimating where the robot is: wheel odometry, EKF-SLAM on marker landmarks, and
//! Monte-Carlo localisation with the lidar on a known map.

pub mod config;
pub mod ekf;
pub mod ellipse;
mod joseph;
pub mod mcl;
pub mod motion;
pub mod odometry;
