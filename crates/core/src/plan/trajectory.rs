//! A time-parameterised path (seed 004 section B: `[{x, y, kappa, v, t, s}]`).

use crate::geometry::Point2;

/// One sample of a trajectory.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TrajectoryPoint {
    pub position: Point2,
    /// Direction of travel, radians.
    pub heading: f64,
    /// Signed curvature, 1/m (positive turns left).
    pub curvature: f64,
    /// Arc length from the start, metres.
    pub s: f64,
    /// Planned speed, m/s.
    pub v: f64,
    /// Planned time from the start, seconds.
    pub t: f64,
}

/// Samples ordered by arc length; the last one is the goal.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Trajectory {
    pub points: Vec<TrajectoryPoint>,
}

impl Trajectory {
    pub fn new(points: Vec<TrajectoryPoint>) -> Self {
        Self { points }
    }

    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Total arc length, metres.
    pub fn length(&self) -> f64 {
        self.points.last().map_or(0.0, |p| p.s)
    }

    /// Planned duration, seconds.
    pub fn duration(&self) -> f64 {
        self.points.last().map_or(0.0, |p| p.t)
    }

    pub fn goal(&self) -> Option<Point2> {
        self.points.last().map(|p| p.position)
    }
}
