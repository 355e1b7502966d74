//! What the mission reads each control step and what it asks for: the contract between
//! the pure state machine and the console that runs it.

use crate::data::{GripperCommand, GripperState};
use crate::geometry::{Point2, Pose2, Twist};
use crate::map::costmap::Costmap;
use std::collections::BTreeMap;

/// How the path the mission asked for is going (the console plans and follows it).
#[derive(Clone, Debug, PartialEq)]
pub enum PathStatus {
    /// No path asked for, or the last one was dropped.
    Idle,
    Following {
        remaining: f64,
    },
    Arrived,
    /// The console could not plan: the reason, as the planner gave it.
    NoPath(String),
}

/// Everything the mission may look at in one step.
#[derive(Clone, Copy, Debug)]
pub struct Inputs<'a> {
    /// Session time, seconds.
    pub t: f64,
    /// The filter's pose.
    pub pose: Pose2,
    /// The filter's landmark means by marker ID.
    pub landmarks: &'a BTreeMap<u32, Point2>,
    /// Marker IDs in the newest camera frame (empty when no frame arrived this step).
    pub seen: &'a [u32],
    /// Whether a camera frame arrived this step (so an empty `seen` means "nothing in view").
    pub camera_frame: bool,
    pub gripper: Option<GripperState>,
    pub path: &'a PathStatus,
    pub map: &'a Costmap,
    /// The cells of `map` the lidar found occupied (row-major, the same size), or empty
    /// without a lidar.
    pub occupied: &'a [bool],
    /// The newest lidar scan's hits in the robot's frame now, or empty without one.
    pub scan: &'a [Point2],
    /// The filter's position uncertainty: the standard deviation along its worst
    /// direction, metres.
    pub position_std: f64,
    /// Another estimator vouches for the pose (MCL converged on a known map): a view
    /// without markers is then no sign of being lost.
    pub localized: bool,
    /// The arm's joints as the robot last reported them, radians (none without an arm,
    /// or before a report).
    pub arm: Option<[f64; 4]>,
    /// Whether a block may be picked up now: false while the arm does not answer (seed
    /// 000 §7.2.1, skip manipulation), so blocks wait and exploring goes on.
    pub can_pick: bool,
}

/// How the robot should move this step.
#[derive(Clone, Debug, PartialEq)]
pub enum Motion {
    /// Stand still.
    Stop,
    /// Drive this twist directly (scans, final approaches, alignment, backing off).
    Drive(Twist),
    /// Plan a path to `goal` and start following it; `label` names it in the log.
    PlanTo { goal: Point2, label: String },
    /// Keep following the current path.
    Follow,
}

/// How a log line should look: the console's one scale of levels.
pub use crate::data::Level;

/// The mission's answer for one step.
#[derive(Clone, Debug, PartialEq)]
pub struct Outputs {
    pub motion: Motion,
    pub gripper: Option<GripperCommand>,
    /// Joints the arm should move to, radians (with an arm in the mission's hands).
    pub arm: Option<[f64; 4]>,
    /// Lines for the log, in seed 001's words where it has them.
    pub log: Vec<(Level, String)>,
    /// Marker IDs the filter must not use now: those of the block in the gripper, and of
    /// delivered blocks (they moved, so their landmarks would mislead it).
    pub ignore_markers: Vec<u32>,
    /// The mission gave up and hands the robot to manual control (seed 001 recovery).
    pub to_manual: bool,
}

impl Outputs {
    pub fn new(motion: Motion) -> Self {
        Self {
            motion,
            gripper: None,
            arm: None,
            log: Vec::new(),
            ignore_markers: Vec::new(),
            to_manual: false,
        }
    }
}

#[cfg(test)]
impl<'a> Inputs<'a> {
    /// A step at `t` with the robot at `pose` on `map` (the lidar's `occupied` cells of
    /// it), nothing in view, no landmarks and no path asked for: where the mission's unit
    /// tests start from.
    pub(crate) fn quiet(t: f64, pose: Pose2, map: &'a Costmap, occupied: &'a [bool]) -> Self {
        static NO_LANDMARKS: BTreeMap<u32, Point2> = BTreeMap::new();
        static IDLE: PathStatus = PathStatus::Idle;
        Self {
            t,
            pose,
            landmarks: &NO_LANDMARKS,
            seen: &[],
            camera_frame: false,
            gripper: None,
            path: &IDLE,
            map,
            occupied,
            scan: &[],
            position_std: 0.01,
            localized: false,
            arm: None,
            can_pick: true,
        }
    }
}
