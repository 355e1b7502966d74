//! The one interface every path-following law implements.

use super::tracking::Progress;
use crate::geometry::{Pose2, Twist};
use crate::plan::trajectory::Trajectory;
use std::fmt::Debug;

/// The robot's speed limits, m/s and rad/s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits {
    pub max_linear: f64,
    pub max_angular: f64,
}

/// A path-following law: pose and progress in, velocity command out. It never reads a clock;
/// `dt` is the time since the previous step, seconds.
pub trait PathController: Debug + Send {
    /// The command for a robot at `pose`. `progress.speed` is the reference speed: the
    /// profile's at the projection, floored at the follower's minimum speed.
    fn step(&mut self, pose: Pose2, trajectory: &Trajectory, progress: &Progress, dt: f64)
    -> Twist;

    /// Forgets integrators, filters and targets (a new path, or a switch of controller).
    fn reset(&mut self);

    fn name(&self) -> &'static str;
}
