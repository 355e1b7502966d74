//! Correction by one marker sighting (seed 001 section 3), and landmarks entering the
//! state: from their first sightings, or known beforehand.

use super::{EkfSlam, Outcome};
use crate::data::MarkerSighting;
use crate::geometry::{Point2, wrap_angle};
use crate::slam::downdate::{into_downdate_factor, symmetric_downdate};
use nalgebra::{DMatrix, Matrix2, Matrix2x3, Vector2};

impl EkfSlam {
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
        // P H^T, N x 2, from the five columns the sighting involves: O(n).
        let (mut u0, mut u1) = self.times_h_transpose(&h_r, &h_l, l);
        // S = H P H^T + R, 2x2, from U's rows at the involved states.
        let mut hph = Matrix2::zeros();
        for j in 0..3 {
            hph += h_r.column(j) * Vector2::new(u0[j], u1[j]).transpose();
        }
        for j in 0..2 {
            hph += h_l.column(j) * Vector2::new(u0[l + j], u1[l + j]).transpose();
        }
        let s_mat = (hph + hph.transpose()) * 0.5 + self.r;
        let Some(chol) = s_mat.cholesky() else {
            return Outcome::Invalid;
        };
        // Innovation, bearing wrapped to (-pi, pi].
        let nu = Vector2::new(s.range - expected[0], wrap_angle(s.bearing - expected[1]));
        let whitened = chol.solve(&nu);
        let d2 = nu.dot(&whitened);
        if d2 > self.gate {
            self.rejected += 1;
            return Outcome::Rejected(d2);
        }
        // mu += K nu with K = U S^-1.
        for (m, (a, b)) in self.mu.iter_mut().zip(u0.iter().zip(&u1)) {
            *m += a * whitened[0] + b * whitened[1];
        }
        self.mu[2] = wrap_angle(self.mu[2]);
        // P <- P - U S^-1 U^T = P - W W^T (see `downdate`): symmetric by construction,
        // one pass over the stored triangle.
        into_downdate_factor(&mut u0, &mut u1, &chol.l());
        symmetric_downdate(&mut self.sigma, &u0, &u1);
        self.hold_pose_floor();
        self.sightings[slot] += 1;
        Outcome::Corrected(d2)
    }

    /// U = P H^T as two columns, for H nonzero in the robot's three states and the
    /// landmark's two at `l`: reads the stored triangle's columns where they are
    /// contiguous (rows at or below the column) and its rows above.
    fn times_h_transpose(
        &self,
        h_r: &Matrix2x3<f64>,
        h_l: &Matrix2<f64>,
        l: usize,
    ) -> (Vec<f64>, Vec<f64>) {
        let n = self.sigma.nrows();
        let data = self.sigma.as_slice();
        let (mut u0, mut u1) = (vec![0.0; n], vec![0.0; n]);
        let involved = [
            (0, h_r[(0, 0)], h_r[(1, 0)]),
            (1, h_r[(0, 1)], h_r[(1, 1)]),
            (2, h_r[(0, 2)], h_r[(1, 2)]),
            (l, h_l[(0, 0)], h_l[(1, 0)]),
            (l + 1, h_l[(0, 1)], h_l[(1, 1)]),
        ];
        for (c, a, b) in involved {
            // Rows above the diagonal: P[i, c] = P[c, i], stored in column i at row c.
            for i in 0..c {
                let v = data[i * n + c];
                u0[i] += a * v;
                u1[i] += b * v;
            }
            let column = &data[c * n + c..(c + 1) * n];
            for ((x0, x1), v) in u0[c..].iter_mut().zip(&mut u1[c..]).zip(column) {
                *x0 += a * v;
                *x1 += b * v;
            }
        }
        (u0, u1)
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
