//! A keyframe's own data beside its node's pose: the scan as received, its points thinned
//! for matching, the path length to it and its pose's covariance; and the odometry noise
//! between keyframes.

use crate::data::LaserScan;
use crate::geometry::{Point2, Pose2};
use nalgebra::{Matrix3, Vector3};

#[derive(Clone, Debug)]
pub struct Keyframe {
    /// The odometry pose the scan was taken at (this session's odometry frame).
    pub odom: Pose2,
    pub scan: LaserScan,
    /// The scan's hits in the robot frame, no two closer than the matching grid's cell.
    pub points: Vec<Point2>,
    /// Path length from the first keyframe, metres.
    pub travelled: f64,
    /// The pose's covariance in the map frame (propagated along the chain: an
    /// approximation of the graph's marginal, refreshed where a loop closes).
    pub covariance: Matrix3<f64>,
}

impl Keyframe {
    /// A keyframe of `scan` taken at odometry pose `odom`.
    pub fn new(odom: Pose2, scan: LaserScan, resolution: f64, travelled: f64) -> Keyframe {
        let points = thin(&scan, resolution);
        Keyframe {
            odom,
            scan,
            points,
            travelled,
            covariance: Matrix3::zeros(),
        }
    }
}

/// The scan's hits (REP-117: only ranges within [range_min, range_max]) in the robot
/// frame, each at least `spacing` from the one kept before it: near walls, where beams
/// crowd, they would otherwise outweigh the far ones.
pub fn thin(scan: &LaserScan, spacing: f64) -> Vec<Point2> {
    let mut out: Vec<Point2> = Vec::with_capacity(scan.ranges.len());
    for p in scan.hits(Pose2::default()) {
        if out.last().is_none_or(|q| q.distance(p) >= spacing) {
            out.push(p);
        }
    }
    out
}

/// The covariance odometry gathers over `step` (robot frame): a share `k` of the distance
/// along and across, and of the angle turned plus a little per metre (the odometry motion
/// model's alphas, Probabilistic Robotics table 5.6, as standard deviations).
pub fn odometry_noise(step: Pose2, k: f64) -> Matrix3<f64> {
    let d = step.x.hypot(step.y);
    let a = step.theta.abs();
    let along = k * d + 1e-4;
    let across = 0.5 * k * d + 1e-4;
    let turn = k * a + 0.5 * k * d + 1e-4;
    Matrix3::from_diagonal(&Vector3::new(along * along, across * across, turn * turn))
}
