//! EKF-SLAM on marker landmarks (seed 001 section 3): state [x, y, theta, l1x, l1y, ...]
//! with full covariance. A sighting touches the robot and one landmark only, so the gain
//! costs O(n) and the covariance update O(n^2); prediction touches the robot's rows: O(n).
//! Sigma is symmetric, so only its lower triangle (row >= column) is stored and updated:
//! half the memory traffic of the O(n^2) update, which is memory-bound at large n.

mod correction;
#[cfg(test)]
mod tests;

use super::config::SlamConfig;
use super::motion::{control_jacobian, state_jacobian};
use super::odometry::predict_pose;
use crate::data::WheelTravel;
use crate::geometry::{Point2, Pose2, wrap_angle};
use nalgebra::{DMatrix, DVector, Matrix2, Matrix3, Vector3};
use std::collections::HashMap;

/// The least pose uncertainty the filter keeps, standard deviations: position (m) and
/// heading (rad). Its job is numerical: variances of 1e-8 sit eight orders above the
/// rounding of unit-sized entries and far below what any encoder or camera resolves, so
/// the floor keeps the pose block definite without shaping the estimate. navdeck's choice.
const POSE_STD_FLOOR: (f64, f64) = (1e-4, 1e-4);

/// What became of one sighting.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Outcome {
    /// Corrected the state; the squared Mahalanobis distance of its innovation.
    Corrected(f64),
    /// Entered the state as a new landmark.
    Added,
    /// Counted towards `min_sightings`, not yet in the state.
    Pending,
    /// Beyond the chi-square gate: dropped and counted.
    Rejected(f64),
    /// Not a usable number (non-finite range or bearing, range not positive).
    Invalid,
}

/// One landmark as the filter believes it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LandmarkEstimate {
    pub id: u32,
    pub mean: Point2,
    pub covariance: Matrix2<f64>,
    pub sightings: u32,
}

/// The filter.
#[derive(Clone, Debug)]
pub struct EkfSlam {
    mu: DVector<f64>,
    sigma: DMatrix<f64>,
    /// Landmark slot -> marker ID, and back.
    ids: Vec<u32>,
    slots: HashMap<u32, usize>,
    sightings: Vec<u32>,
    pending: HashMap<u32, u32>,
    rejected: u64,
    track: f64,
    /// Wheel travel noise per metre of travel: motor_std / (2 pi) (see `SlamConfig`).
    travel_std_per_m: f64,
    r: Matrix2<f64>,
    min_sightings: u32,
    fixed_initial_variance: Option<f64>,
    gate: f64,
}

impl EkfSlam {
    /// A filter with no landmarks, the robot at `start` with covariance `start_cov`.
    pub fn new(start: Pose2, start_cov: Matrix3<f64>, config: &SlamConfig, track: f64) -> Self {
        let mut sigma = DMatrix::zeros(3, 3);
        sigma.fixed_view_mut::<3, 3>(0, 0).copy_from(&start_cov);
        let angle = config.angle_std_deg.to_radians();
        Self {
            mu: DVector::from_column_slice(&[start.x, start.y, start.theta]),
            sigma,
            ids: Vec::new(),
            slots: HashMap::new(),
            sightings: Vec::new(),
            pending: HashMap::new(),
            rejected: 0,
            track,
            travel_std_per_m: config.motor_std_deg.to_radians() / std::f64::consts::TAU,
            r: Matrix2::new(config.dist_std.powi(2), 0.0, 0.0, angle * angle),
            min_sightings: config.min_sightings.max(1),
            fixed_initial_variance: config.fixed_initial_variance,
            gate: config.gate_chi2,
        }
    }

    pub fn pose(&self) -> Pose2 {
        Pose2::new(self.mu[0], self.mu[1], self.mu[2])
    }

    pub fn pose_covariance(&self) -> Matrix3<f64> {
        Matrix3::from_fn(|i, j| self.sym(i, j))
    }

    /// Sigma[i, j] read from the stored lower triangle.
    fn sym(&self, i: usize, j: usize) -> f64 {
        if i >= j {
            self.sigma[(i, j)]
        } else {
            self.sigma[(j, i)]
        }
    }

    pub fn landmark_count(&self) -> usize {
        self.ids.len()
    }

    pub fn rejected(&self) -> u64 {
        self.rejected
    }

    /// The full covariance, rebuilt from the stored triangle (O(n^2): for checks).
    pub fn covariance(&self) -> DMatrix<f64> {
        let n = self.sigma.ncols();
        DMatrix::from_fn(n, n, |i, j| self.sym(i, j))
    }

    pub fn landmarks(&self) -> impl Iterator<Item = LandmarkEstimate> + '_ {
        (0..self.ids.len()).map(|slot| self.estimate(slot))
    }

    pub fn landmark(&self, id: u32) -> Option<LandmarkEstimate> {
        self.slots.get(&id).map(|&slot| self.estimate(slot))
    }

    /// Puts the robot at `pose` with covariance `cov`, as another estimator (MCL) or the
    /// user placed it: the landmarks keep their estimates, and their correlation with the
    /// robot is dropped, since the new pose was not derived from them.
    pub fn relocate(&mut self, pose: Pose2, cov: &Matrix3<f64>) {
        self.mu[0] = pose.x;
        self.mu[1] = pose.y;
        self.mu[2] = wrap_angle(pose.theta);
        for i in 0..3 {
            for j in 0..=i {
                self.sigma[(i, j)] = cov[(i, j)];
            }
        }
        for r in 3..self.sigma.nrows() {
            for c in 0..3 {
                self.sigma[(r, c)] = 0.0;
            }
        }
    }

    /// Drops landmark `id` from the state, as when the thing it marks was moved: the
    /// marginal of a Gaussian over the other variables is its mean and covariance with the
    /// dropped variables' rows and columns struck out. A later sighting starts it afresh.
    pub fn forget(&mut self, id: u32) -> bool {
        self.pending.remove(&id);
        let Some(slot) = self.slots.remove(&id) else {
            return false;
        };
        let i = 3 + 2 * slot;
        self.mu = std::mem::take(&mut self.mu).remove_rows(i, 2);
        self.sigma = std::mem::take(&mut self.sigma)
            .remove_rows(i, 2)
            .remove_columns(i, 2);
        self.ids.remove(slot);
        self.sightings.remove(slot);
        for (k, &other) in self.ids.iter().enumerate().skip(slot) {
            self.slots.insert(other, k);
        }
        true
    }

    fn estimate(&self, slot: usize) -> LandmarkEstimate {
        let i = 3 + 2 * slot;
        LandmarkEstimate {
            id: self.ids[slot],
            mean: Point2::new(self.mu[i], self.mu[i + 1]),
            covariance: Matrix2::from_fn(|a, b| self.sym(i + a, i + b)),
            sightings: self.sightings[slot],
        }
    }

    /// Prediction from wheel travel: Sigma = G Sigma G^T + V Q V^T (seed 001 section 3),
    /// on the robot's rows and columns only.
    pub fn predict(&mut self, wheels: WheelTravel) {
        if !(wheels.left.is_finite() && wheels.right.is_finite()) {
            return;
        }
        let pose = self.pose();
        let g = state_jacobian(pose, wheels, self.track);
        let v = control_jacobian(pose, wheels, self.track);
        let next = predict_pose(pose, wheels, self.track);
        self.mu[0] = next.x;
        self.mu[1] = next.y;
        self.mu[2] = next.theta;
        let (sl, sr) = (
            self.travel_std_per_m * wheels.left.abs(),
            self.travel_std_per_m * wheels.right.abs(),
        );
        let q = Matrix2::new(sl * sl, 0.0, 0.0, sr * sr);
        let rr = self.pose_covariance();
        let new_rr = g * rr * g.transpose() + v * q * v.transpose();
        let new_rr = (new_rr + new_rr.transpose()) * 0.5;
        self.sigma.fixed_view_mut::<3, 3>(0, 0).copy_from(&new_rr);
        let n = self.sigma.ncols();
        if n > 3 {
            // Sigma_lr <- Sigma_lr G^T (the stored mirror of Sigma_rl <- G Sigma_rl), row
            // by row in place: the robot's three columns are contiguous below row 3.
            let (c0, rest) = self.sigma.as_mut_slice().split_at_mut(n);
            let (c1, rest) = rest.split_at_mut(n);
            let c2 = &mut rest[..n];
            for ((a, b), c) in c0[3..].iter_mut().zip(&mut c1[3..]).zip(&mut c2[3..]) {
                let row = Vector3::new(*a, *b, *c);
                let new_row = g * row;
                (*a, *b, *c) = (new_row[0], new_row[1], new_row[2]);
            }
        }
        self.hold_pose_floor();
    }

    /// Keeps the pose block's uncertainty at or above what wheel encoders resolve: two
    /// wheels' noise spans only two of the pose's three directions, and rounding in many
    /// corrections can push a collapsed block below zero. Adding `(1 - l) D^2` (l the
    /// smallest eigenvalue of `D^-1 P D^-1`) adds a positive semidefinite term, so the
    /// whole covariance stays positive semidefinite and the pose block definite.
    fn hold_pose_floor(&mut self) {
        let d = Vector3::new(POSE_STD_FLOOR.0, POSE_STD_FLOOR.0, POSE_STD_FLOOR.1);
        let p = self.pose_covariance();
        let scaled = Matrix3::from_fn(|i, j| p[(i, j)] / (d[i] * d[j]));
        // Cheap first: the smallest eigenvalue is at least 1 when scaled - I is definite.
        if (scaled - Matrix3::identity()).cholesky().is_some() {
            return;
        }
        let smallest = scaled.symmetric_eigenvalues().min();
        // A non-finite eigenvalue (a broken block) is lifted by one floor.
        let lift = if smallest.is_finite() {
            1.0 - smallest
        } else {
            1.0
        };
        if lift > 0.0 {
            for i in 0..3 {
                self.sigma[(i, i)] += lift * d[i] * d[i];
            }
        }
    }
}
