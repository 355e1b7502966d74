//! Estimating where the robot is: wheel odometry now, EKF-SLAM later.

pub mod config;
pub mod ekf;
pub mod ellipse;
pub mod motion;
pub mod odometry;
