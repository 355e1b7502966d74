//! Path-following controllers: they turn a pose and a trajectory into a twist; and the
//! collision monitor, which holds back any command that would drive into an obstacle.
//! The core never reads a clock or touches a terminal: poses and `dt` are passed in.

pub mod collision_monitor;
pub mod config;
pub mod controller;
pub mod fleet_yield;
pub mod follower;
pub mod hybrid;
pub mod lane;
pub mod pid;
pub mod pid_follower;
pub mod pure_pursuit;
#[cfg(test)]
mod test_paths;
pub mod tracking;

pub use config::{ControllerKind, FollowConfig};
pub use controller::{Limits, PathController};
pub use follower::{FollowStatus, FollowStep, Follower};
pub use tracking::{Progress, ProgressTracker};
