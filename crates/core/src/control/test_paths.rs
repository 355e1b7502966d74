//! Hand-built trajectories for the unit tests.

use crate::geometry::Point2;
use crate::plan::trajectory::{Trajectory, TrajectoryPoint};

/// Samples every ~0.05 m along `f(s) -> (point, heading, curvature)` at 0.2 m/s.
pub fn path(length: f64, f: impl Fn(f64) -> (Point2, f64, f64)) -> Trajectory {
    let n = (length / 0.05).round().max(1.0) as usize;
    Trajectory::new(
        (0..=n)
            .map(|k| {
                let s = length * k as f64 / n as f64;
                let (position, heading, curvature) = f(s);
                TrajectoryPoint {
                    position,
                    heading,
                    curvature,
                    s,
                    v: 0.2,
                    t: s / 0.2,
                }
            })
            .collect(),
    )
}

/// Along +x from the origin.
pub fn line(length: f64) -> Trajectory {
    path(length, |s| (Point2::new(s, 0.0), 0.0, 0.0))
}

/// A left turn of radius `r` from the origin, heading +x at the start.
pub fn arc(r: f64, length: f64) -> Trajectory {
    path(length, |s| {
        let a = s / r;
        (Point2::new(r * a.sin(), r - r * a.cos()), a, 1.0 / r)
    })
}
