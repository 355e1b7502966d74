//! What the filter shows of itself: its hypotheses, the pose now, the spread, its state.

use super::{Mcl, Particle};
use crate::geometry::{Point2, Pose2, wrap_angle};
use crate::slam::mcl::status::{Phase, Status};
use nalgebra::Matrix3;

impl Mcl {
    /// The hypotheses the filter weighs: each cluster's mean pose and weight, heaviest
    /// first.
    pub fn hypotheses(&self) -> &[(Pose2, f64)] {
        &self.estimate.hypotheses
    }

    /// The estimate now, given the odometry pose now: the estimate at the last update
    /// moved by what the odometry measured since (REP 105's map -> odom at work).
    pub fn pose(&self, odom: Pose2) -> Pose2 {
        let at = self.estimate.pose;
        let Some(last) = self.odom_at_update else {
            return at;
        };
        // The odometry's motion since the update, in the robot's frame then.
        let (s, c) = last.theta.sin_cos();
        let (dx, dy) = (odom.x - last.x, odom.y - last.y);
        let local = Point2::new(c * dx + s * dy, -s * dx + c * dy);
        let here = at.transform_point(local);
        Pose2::new(
            here.x,
            here.y,
            wrap_angle(at.theta + odom.theta - last.theta),
        )
    }

    /// The covariance (x, y, θ) of the heaviest cluster.
    pub fn covariance(&self) -> Matrix3<f64> {
        self.estimate.covariance
    }

    /// The estimate's position standard deviation along its worst direction, metres.
    pub fn position_std(&self) -> f64 {
        let c = self
            .estimate
            .covariance
            .fixed_view::<2, 2>(0, 0)
            .into_owned();
        crate::slam::ellipse::axes(&c, 1.0).0
    }

    pub fn particles(&self) -> &[Particle] {
        &self.particles
    }

    pub fn status(&self) -> Status {
        Status {
            particles: self.particles.len(),
            effective: self.effective,
            cluster_weight: self.estimate.weight,
            clusters: self.estimate.clusters,
            converged: self.converged,
            phase: match (self.converged, self.lost) {
                (true, _) => Phase::Localised,
                (false, true) => Phase::Lost,
                (false, false) => Phase::Localising,
            },
            spread: self.position_std(),
            random_share: self.random_share,
            updates: self.updates,
        }
    }
}
