//! What exploration remembers: the goals and markers it reached, the looks it took at
//! potential blocks and unexplained objects, what the camera has looked at, and the
//! goals it gave up.

use super::coverage::Coverage;
use crate::geometry::Point2;
use std::collections::BTreeMap;

/// A small object the lidar mapped and no marker explains, or a block let go where it
/// did not count, and the looks taken at it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Unexplained {
    pub at: Point2,
    /// Direction of the first look, from the object, radians; later looks turn 90° on.
    pub first: f64,
    pub looks: u32,
    /// A block (odd marker) let go where it did not count: looked at until it is found
    /// again, whether or not the lidar's map shows it apart from its neighbours.
    pub let_go: Option<u32>,
}

impl Unexplained {
    /// One not looked at yet, at `at`, the first look from the side of `robot`.
    pub fn new(at: Point2, robot: Point2, let_go: Option<u32>) -> Self {
        Self {
            at,
            first: (robot.y - at.y).atan2(robot.x - at.x),
            looks: 0,
            let_go,
        }
    }
}

/// Where exploration has been and what it has looked at: a goal reached is not chosen
/// again.
#[derive(Clone, Debug, Default)]
pub(super) struct Explored {
    pub visited_markers: Vec<u32>,
    pub visited_goals: Vec<Point2>,
    /// Looks taken at each potential block (odd marker), from different sides.
    pub potential_looks: BTreeMap<u32, u32>,
    /// Small objects the lidar mapped that no marker explained when first met.
    pub unexplained: Vec<Unexplained>,
    /// What the camera has looked at.
    pub coverage: Coverage,
    /// The exploration targets the last choice weighed (frontiers, unseen space), for
    /// the map.
    pub candidates: Vec<Point2>,
}

/// Exploration goals (frontier points, marker IDs) the planner could not reach, and
/// the rounds of turning and trying them again so far.
#[derive(Clone, Debug, Default)]
pub(super) struct GivenUp {
    pub goals: Vec<Point2>,
    pub markers: Vec<u32>,
    pub retry_rounds: u32,
}
