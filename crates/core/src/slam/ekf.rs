//! EKF-SLAM on marker landmarks (seed 001 section 3): state [x, y, theta, l1x, l1y, ...]
//! with full covariance. A sighting touches the robot and one landmark only, so the gain
//! costs O(n) and the covariance update O(n^2); prediction touches the robot's rows: O(n).
//! Sigma is symmetric, so only its lower triangle (row >= column) is stored and updated:
//! half the memory traffic of the O(n^2) update, which is memory-bound at large n.

use super::config::SlamConfig;
use super::joseph::joseph_update;
use super::motion::{control_jacobian, state_jacobian};
use super::odometry::predict_pose;
use crate::data::{MarkerSighting, WheelTravel};
use crate::geometry::{Point2, Pose2, wrap_angle};
use nalgebra::{DMatrix, DVector, Matrix2, Matrix2x3, Matrix3, Vector2, Vector3};
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

    /// The x-y block of the pose covariance.
    pub fn position_covariance(&self) -> Matrix2<f64> {
        Matrix2::from_fn(|i, j| self.sym(i, j))
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
            // Sigma_lr <- Sigma_lr G^T (the stored mirror of Sigma_rl <- G Sigma_rl).
            let lr = self.sigma.view((3, 0), (n - 3, 3)) * g.transpose();
            self.sigma.view_mut((3, 0), (n - 3, 3)).copy_from(&lr);
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

    /// Correction by one sighting, associated by marker ID (seed 001's data association).
    pub fn correct(&mut self, s: MarkerSighting) -> Outcome {
        if !(s.range.is_finite() && s.bearing.is_finite() && s.range > 0.0) {
            return Outcome::Invalid;
        }
        let Some(&slot) = self.slots.get(&s.id) else {
            let count = self.pending.entry(s.id).or_insert(0);
            *count += 1;
            if *count < self.min_sightings {
                return Outcome::Pending;
            }
            self.pending.remove(&s.id);
            self.add_landmark(s);
            return Outcome::Added;
        };
        let l = 3 + 2 * slot;
        let (x, y, th) = (self.mu[0], self.mu[1], self.mu[2]);
        let (dx, dy) = (self.mu[l] - x, self.mu[l + 1] - y);
        let q = dx * dx + dy * dy;
        let range = q.sqrt();
        // Seed 001: r = sqrt(dx^2 + dy^2), alpha = atan2(dy, dx) - theta.
        let expected = Vector2::new(range, wrap_angle(dy.atan2(dx) - th));
        // Seed 001's H, split into the robot's 2x3 and the landmark's 2x2 blocks.
        let h_r = Matrix2x3::new(-dx / range, -dy / range, 0.0, dy / q, -dx / q, -1.0);
        let h_l = Matrix2::new(dx / range, dy / range, -dy / q, dx / q);
        let n = self.sigma.ncols();
        // P H^T, N x 2, from the five columns the sighting involves: O(n).
        let mut pht = DMatrix::<f64>::zeros(n, 2);
        let involved = [
            (0, h_r[(0, 0)], h_r[(1, 0)]),
            (1, h_r[(0, 1)], h_r[(1, 1)]),
            (2, h_r[(0, 2)], h_r[(1, 2)]),
            (l, h_l[(0, 0)], h_l[(1, 0)]),
            (l + 1, h_l[(0, 1)], h_l[(1, 1)]),
        ];
        for (c, a, b) in involved {
            for i in 0..n {
                let v = self.sym(i, c);
                pht[(i, 0)] += a * v;
                pht[(i, 1)] += b * v;
            }
        }
        // S = H P H^T + R, 2x2.
        let rows = |i: usize| Vector2::new(pht[(i, 0)], pht[(i, 1)]).transpose();
        let mut hph = Matrix2::zeros();
        for (j, i) in [0, 1, 2].into_iter().enumerate() {
            hph += h_r.column(j) * rows(i);
        }
        for (j, i) in [l, l + 1].into_iter().enumerate() {
            hph += h_l.column(j) * rows(i);
        }
        let s_mat = (hph + hph.transpose()) * 0.5 + self.r;
        let Some(s_inv) = s_mat.try_inverse() else {
            return Outcome::Invalid;
        };
        // Innovation, bearing wrapped to (-pi, pi].
        let nu = Vector2::new(s.range - expected[0], wrap_angle(s.bearing - expected[1]));
        let d2 = (nu.transpose() * s_inv * nu)[0];
        if d2 > self.gate {
            self.rejected += 1;
            return Outcome::Rejected(d2);
        }
        let k = &pht * s_inv;
        self.mu += &k * nu;
        self.mu[2] = wrap_angle(self.mu[2]);
        // Joseph form (Bar-Shalom et al. 5.2.3): (I - K H) P (I - K H)^T + K R K^T,
        // expanded with U = P H^T to P - K U^T - U K^T + K S K^T: symmetric by
        // construction, first-order insensitive to rounding in K, O(n^2) on the triangle.
        joseph_update(&mut self.sigma, &k, &pht, &s_mat);
        self.hold_pose_floor();
        self.sightings[slot] += 1;
        Outcome::Corrected(d2)
    }

    /// Puts a landmark into the state from its first sighting (inverse observation model).
    /// Adds a landmark known beforehand (from a saved map) with its own covariance and no
    /// correlation with the rest: the filter then localises against it. A landmark already
    /// in the state is left as it is; returns whether it was added.
    pub fn add_prior(
        &mut self,
        id: u32,
        mean: Point2,
        covariance: Matrix2<f64>,
        sightings: u32,
    ) -> bool {
        let finite =
            mean.x.is_finite() && mean.y.is_finite() && covariance.iter().all(|v| v.is_finite());
        if self.slots.contains_key(&id) || !finite {
            return false;
        }
        let n = self.sigma.ncols();
        self.mu = self.mu.clone().insert_rows(n, 2, 0.0);
        self.mu[n] = mean.x;
        self.mu[n + 1] = mean.y;
        let mut sigma = std::mem::replace(&mut self.sigma, DMatrix::zeros(0, 0));
        sigma = sigma.resize(n + 2, n + 2, 0.0);
        let sym = (covariance + covariance.transpose()) * 0.5;
        sigma.fixed_view_mut::<2, 2>(n, n).copy_from(&sym);
        self.sigma = sigma;
        self.slots.insert(id, self.ids.len());
        self.ids.push(id);
        self.sightings.push(sightings.max(1));
        self.pending.remove(&id);
        true
    }

    fn add_landmark(&mut self, s: MarkerSighting) {
        let (x, y, th) = (self.mu[0], self.mu[1], self.mu[2]);
        let (sin, cos) = (th + s.bearing).sin_cos();
        let mean = Vector2::new(x + s.range * cos, y + s.range * sin);
        let n = self.sigma.ncols();
        self.mu = self.mu.clone().insert_rows(n, 2, 0.0);
        self.mu[n] = mean[0];
        self.mu[n + 1] = mean[1];
        let mut sigma = std::mem::replace(&mut self.sigma, DMatrix::zeros(0, 0));
        sigma = sigma.resize(n + 2, n + 2, 0.0);
        match self.fixed_initial_variance {
            Some(v) => {
                // Seed 001 "Landmark Management": sigma^2 = 0.5 m^2, uncorrelated.
                sigma[(n, n)] = v;
                sigma[(n + 1, n + 1)] = v;
            }
            None => {
                // m = (x + r cos(theta + a), y + r sin(theta + a)): Jacobians in pose and (r, a).
                let gx = Matrix2x3::new(1.0, 0.0, -s.range * sin, 0.0, 1.0, s.range * cos);
                let gz = Matrix2::new(cos, -s.range * sin, sin, s.range * cos);
                let robot_rows =
                    DMatrix::from_fn(
                        3,
                        n,
                        |i, j| {
                            if i >= j { sigma[(i, j)] } else { sigma[(j, i)] }
                        },
                    );
                let rows = gx * robot_rows;
                let ll = gx * rows.columns(0, 3).transpose() + gz * self.r * gz.transpose();
                sigma.view_mut((n, 0), (2, n)).copy_from(&rows);
                let ll = (ll + ll.transpose()) * 0.5;
                sigma.fixed_view_mut::<2, 2>(n, n).copy_from(&ll);
            }
        }
        self.sigma = sigma;
        self.slots.insert(s.id, self.ids.len());
        self.ids.push(s.id);
        self.sightings.push(1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn filter(start_var: f64) -> EkfSlam {
        EkfSlam::new(
            Pose2::default(),
            Matrix3::from_diagonal_element(start_var),
            &SlamConfig::default(),
            0.11,
        )
    }

    fn sighting(id: u32, range: f64, bearing: f64) -> MarkerSighting {
        MarkerSighting { id, range, bearing }
    }

    #[test]
    fn straight_prediction_moves_along_heading_and_grows_along_track_variance() {
        // A start uncertainty above the pose floor, so the floor does not act.
        let p0 = 1e-4;
        let mut f = filter(p0);
        f.predict(WheelTravel {
            left: 0.1,
            right: 0.1,
        });
        let p = f.pose();
        assert!((p.x - 0.1).abs() < 1e-15 && p.y == 0.0 && p.theta == 0.0);
        // Hand-worked: G = [[1, 0, 0], [0, 1, l], [0, 0, 1]] and
        // V = [[.5, .5], [-l/2w, l/2w], [-1/w, 1/w]] with l = 0.1, w = 0.11,
        // Q = diag(s^2, s^2), s = 0.1 * (4 deg in rad) / 2 pi.
        let s = 0.1 * 4f64.to_radians() / std::f64::consts::TAU;
        let c = f.pose_covariance();
        assert!((c[(0, 0)] - (p0 + 0.5 * s * s)).abs() < 1e-18);
        let k = 0.1 / (2.0 * 0.11);
        assert!((c[(1, 1)] - (p0 + 0.01 * p0 + 2.0 * k * k * s * s)).abs() < 1e-18);
        assert!((c[(2, 2)] - (p0 + 2.0 * s * s / (0.11 * 0.11))).abs() < 1e-15);
    }

    #[test]
    fn a_known_start_and_rank_two_wheel_noise_still_give_a_definite_pose_block() {
        // Two wheels' noise spans two of three directions: without the floor this block
        // would be singular, and its inverse (for NEES) meaningless.
        let mut f = filter(0.0);
        f.predict(WheelTravel {
            left: 0.1,
            right: 0.1,
        });
        let (sp, sh) = POSE_STD_FLOOR;
        let d = Matrix3::from_diagonal(&Vector3::new(1.0 / sp, 1.0 / sp, 1.0 / sh));
        let scaled = d * f.pose_covariance() * d;
        assert!(scaled.symmetric_eigenvalues().min() >= 1.0 - 1e-9);
        assert!(f.pose_covariance().cholesky().is_some());
    }

    #[test]
    fn standing_still_under_thousands_of_sightings_keeps_the_covariance_definite() {
        let mut f = filter(0.0);
        let marks = [(1, 1.0, 0.3), (2, 1.5, -0.8), (3, 2.0, 2.0), (4, 0.7, -2.5)];
        for round in 0..3000 {
            for &(id, range, bearing) in &marks {
                // Deterministic jitter within the sensor's noise.
                let j = ((round * 7 + id as usize * 13) % 11) as f64 / 10.0 - 0.5;
                f.correct(sighting(id, range + 0.02 * j, bearing + 0.01 * j));
            }
            f.predict(WheelTravel::default());
        }
        let full = f.covariance();
        let smallest = full.clone().symmetric_eigenvalues().min();
        assert!(smallest > 0.0, "smallest eigenvalue {smallest:e}");
        assert!(full.cholesky().is_some());
        assert_eq!(f.rejected(), 0, "a calm filter gates out nothing");
    }

    #[test]
    fn arc_prediction_matches_odometry() {
        let mut f = filter(0.0);
        let w = WheelTravel {
            left: 0.05,
            right: 0.07,
        };
        f.predict(w);
        assert_eq!(f.pose(), predict_pose(Pose2::default(), w, 0.11));
    }

    #[test]
    fn one_landmark_update_with_known_numbers() {
        // Robot certain at the origin; landmark sighted at 2 m dead ahead, then seen at 2.1 m.
        let config = SlamConfig {
            fixed_initial_variance: Some(0.5),
            ..SlamConfig::default()
        };
        let mut f = EkfSlam::new(Pose2::default(), Matrix3::zeros(), &config, 0.11);
        assert_eq!(f.correct(sighting(7, 2.0, 0.0)), Outcome::Added);
        let out = f.correct(sighting(7, 2.1, 0.0));
        // Hand-worked: the range row is H = [dx/r, dy/r] = [1, 0] on the landmark,
        // S = 0.5 + 0.01, K_x = 0.5 / 0.51, so x moves by 0.1 * 0.5 / 0.51.
        let l = f.landmark(7).unwrap();
        assert!((l.mean.x - (2.0 + 0.1 * 0.5 / 0.51)).abs() < 1e-12, "{l:?}");
        assert!((l.covariance[(0, 0)] - (0.5 - 0.25 / 0.51)).abs() < 1e-12);
        // d^2 = 0.1^2 / 0.51
        assert!(matches!(out, Outcome::Corrected(d2) if (d2 - 0.01 / 0.51).abs() < 1e-12));
        assert_eq!(l.sightings, 2);
    }

    #[test]
    fn propagated_initial_uncertainty_follows_the_inverse_model() {
        let mut f = filter(0.0);
        f.correct(sighting(3, 2.0, std::f64::consts::FRAC_PI_2));
        let l = f.landmark(3).unwrap();
        assert!(l.mean.x.abs() < 1e-12 && (l.mean.y - 2.0).abs() < 1e-12);
        // Range noise lies along y, bearing noise (times the range) along x.
        let a = 4f64.to_radians();
        assert!((l.covariance[(1, 1)] - 0.01).abs() < 1e-12);
        assert!((l.covariance[(0, 0)] - 4.0 * a * a).abs() < 1e-12);
    }

    #[test]
    fn outliers_beyond_the_gate_are_rejected_and_counted() {
        let mut f = filter(0.0);
        f.correct(sighting(9, 1.0, 0.0));
        for _ in 0..20 {
            f.correct(sighting(9, 1.0, 0.0));
        }
        assert!(matches!(
            f.correct(sighting(9, 3.0, 0.0)),
            Outcome::Rejected(_)
        ));
        assert_eq!(f.rejected(), 1);
        assert_eq!(f.correct(sighting(9, f64::NAN, 0.0)), Outcome::Invalid);
    }

    #[test]
    fn min_sightings_delays_entry() {
        let config = SlamConfig {
            min_sightings: 3,
            ..SlamConfig::default()
        };
        let mut f = EkfSlam::new(Pose2::default(), Matrix3::zeros(), &config, 0.11);
        assert_eq!(f.correct(sighting(1, 1.0, 0.0)), Outcome::Pending);
        assert_eq!(f.correct(sighting(1, 1.0, 0.0)), Outcome::Pending);
        assert_eq!(f.correct(sighting(1, 1.0, 0.0)), Outcome::Added);
        assert_eq!(f.landmark_count(), 1);
    }

    #[test]
    fn a_forgotten_landmark_leaves_the_others_as_they_were_and_comes_back_afresh() {
        let mut f = filter(0.0);
        f.correct(sighting(1, 1.0, 0.0));
        f.correct(sighting(2, 2.0, 0.5));
        f.correct(sighting(3, 1.5, -0.5));
        let (before2, before3) = (f.landmark(2).unwrap(), f.landmark(3).unwrap());
        assert!(f.forget(2));
        assert!(!f.forget(2), "already gone");
        assert_eq!(f.landmark_count(), 2);
        assert!(f.landmark(2).is_none());
        assert_eq!(f.landmark(3), Some(before3));
        assert_eq!(f.covariance().nrows(), 3 + 2 * 2);
        // Seen somewhere else now: a new landmark, not a rejected sighting.
        assert_eq!(f.correct(sighting(2, 1.0, 2.5)), Outcome::Added);
        assert!(f.landmark(2).unwrap().mean.distance(before2.mean) > 1.0);
        assert_eq!(f.rejected(), 0);
    }
}
