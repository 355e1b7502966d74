//! Estimating where the robot is: wheel odometry and EKF-SLAM on marker landmarks.

pub mod config;
pub mod ekf;
pub mod ellipse;
mod joseph;
pub mod motion;
pub mod odometry;
