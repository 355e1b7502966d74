//! The console's estimator: EKF-SLAM fed from the link, and how well it tracks the twin.

use super::log::Level;
use super::{App, Mode};
use crate::data::{MarkerSighting, WheelTravel};
use crate::geometry::{Pose2, wrap_angle};
use crate::slam::ekf::Outcome;
use nalgebra::{Matrix3, Vector3};

/// Running error statistics against the twin's truth, sampled once per control period.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Accuracy {
    pub samples: u64,
    sum_position_sq: f64,
    sum_heading_sq: f64,
    sum_nees: f64,
}

impl Accuracy {
    /// Adds one sample: the truth, the estimate and the estimate's pose covariance.
    pub fn add(&mut self, truth: Pose2, estimate: Pose2, covariance: &Matrix3<f64>) {
        let e = Vector3::new(
            truth.x - estimate.x,
            truth.y - estimate.y,
            wrap_angle(truth.theta - estimate.theta),
        );
        self.samples += 1;
        self.sum_position_sq += e[0] * e[0] + e[1] * e[1];
        self.sum_heading_sq += e[2] * e[2];
        // NEES = e^T P^-1 e (Bar-Shalom, Estimation with Applications to Tracking, 5.4).
        if let Some(inv) = covariance.try_inverse() {
            self.sum_nees += (e.transpose() * inv * e)[0];
        }
    }

    pub fn position_rmse(&self) -> f64 {
        (self.sum_position_sq / self.samples.max(1) as f64).sqrt()
    }

    pub fn heading_rmse(&self) -> f64 {
        (self.sum_heading_sq / self.samples.max(1) as f64).sqrt()
    }

    pub fn mean_nees(&self) -> f64 {
        self.sum_nees / self.samples.max(1) as f64
    }
}

/// The 95 % chi-square band of one NEES sample with 3 degrees of freedom.
pub const NEES_BAND_3DOF: (f64, f64) = (0.216, 9.348);

impl App {
    pub(super) fn estimate_motion(&mut self, wheels: WheelTravel) {
        self.odometry.update(wheels);
        self.ekf.predict(wheels);
    }

    pub(super) fn estimate_sightings(&mut self, sightings: &[MarkerSighting]) {
        self.camera_frames += 1;
        let mut nearest;
        let mut used = sightings;
        if self.mode == Mode::Race {
            // Seed 001 race mode: reduced SLAM updates, every k-th frame, nearest m.
            let race = &self.config.race;
            if !self
                .camera_frames
                .is_multiple_of(u64::from(race.correct_every))
            {
                return;
            }
            if race.nearest > 0 {
                nearest = sightings.to_vec();
                nearest.sort_by(|a, b| a.range.total_cmp(&b.range));
                nearest.truncate(race.nearest as usize);
                used = &nearest;
            }
        }
        // Gated-out sightings are counted by the filter; non-finite ones are dropped. Markers
        // the mission moved (a block in the gripper or delivered) would mislead it.
        for s in used
            .iter()
            .filter(|s| !self.ignored_markers.contains(&s.id))
        {
            if self.ekf.correct(*s) == Outcome::Added {
                let category = crate::perception::markers::MarkerCategory::of(s.id);
                self.log.push(
                    self.now,
                    Level::Info,
                    format!("new landmark {} ({})", s.id, category.label()),
                );
            }
        }
    }

    /// In race mode, warns once when the position's uncertainty passes the bound.
    pub(super) fn check_race_uncertainty(&mut self) {
        let (major, _, _) = crate::slam::ellipse::axes(&self.ekf.position_covariance(), 1.0);
        let bound = self.config.race.sigma_warning;
        if self.mode == Mode::Race && major > bound && !self.race_sigma_warned {
            self.race_sigma_warned = true;
            self.log.push(
                self.now,
                Level::Warn,
                format!("race: position uncertainty {major:.3} m is past {bound:.3} m; slow down"),
            );
        } else if major <= bound {
            self.race_sigma_warned = false;
        }
    }

    /// One accuracy sample against the twin's truth (twin only).
    pub(super) fn sample_accuracy(&mut self) {
        if let Some(truth) = self.true_pose() {
            let cov = self.ekf.pose_covariance();
            let est = self.ekf.pose();
            self.accuracy.add(truth, est, &cov);
        }
    }

    pub fn accuracy(&self) -> &Accuracy {
        &self.accuracy
    }

    pub fn slam(&self) -> &crate::slam::ekf::EkfSlam {
        &self.ekf
    }

    /// Standard deviations of the pose estimate: x, y (m) and heading (rad).
    pub fn pose_sigma(&self) -> (f64, f64, f64) {
        let c = self.ekf.pose_covariance();
        (c[(0, 0)].sqrt(), c[(1, 1)].sqrt(), c[(2, 2)].sqrt())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rmse_and_nees_of_known_errors() {
        let mut a = Accuracy::default();
        let cov = Matrix3::from_diagonal(&Vector3::new(0.01, 0.01, 0.0004));
        a.add(Pose2::new(0.1, 0.0, 0.0), Pose2::default(), &cov);
        a.add(Pose2::new(0.0, 0.0, 0.02), Pose2::default(), &cov);
        assert!((a.position_rmse() - (0.01f64 / 2.0).sqrt()).abs() < 1e-12);
        assert!((a.heading_rmse() - (0.0004f64 / 2.0).sqrt()).abs() < 1e-12);
        // Each sample's NEES is 1.
        assert!((a.mean_nees() - 1.0).abs() < 1e-9);
    }
}
