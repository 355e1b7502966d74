//! The pilot's estimator: EKF-SLAM fed from the link, and how well it tracks the truth
//! when a simulator knows it.

use super::{Mode, Pilot};
use nalgebra::{Matrix3, Vector3};
use navdeck_core::data::{Level, MarkerSighting, WheelTravel};
use navdeck_core::geometry::{Pose2, wrap_angle};
use navdeck_core::slam::ekf::Outcome;

/// Running error statistics against the twin's truth, sampled once per control period.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Accuracy {
    pub samples: u64,
    sum_position_sq: f64,
    sum_heading_sq: f64,
    sum_nees: f64,
    /// The largest position error of any sample, metres.
    max_position: f64,
    /// Samples whose covariance was not positive definite: NEES is undefined there.
    pub nees_undefined: u64,
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
        self.max_position = self.max_position.max(e[0].hypot(e[1]));
        self.sum_heading_sq += e[2] * e[2];
        // NEES = e^T P^-1 e (Bar-Shalom et al., Estimation with Applications to Tracking and
        // Navigation, 5.4).
        match covariance.cholesky() {
            Some(chol) => self.sum_nees += e.dot(&chol.solve(&e)),
            None => self.nees_undefined += 1,
        }
    }

    pub fn position_rmse(&self) -> f64 {
        (self.sum_position_sq / self.samples.max(1) as f64).sqrt()
    }

    /// The absolute trajectory error's largest position error, metres (0 with no samples).
    pub fn position_max_error(&self) -> f64 {
        self.max_position
    }

    pub fn heading_rmse(&self) -> f64 {
        (self.sum_heading_sq / self.samples.max(1) as f64).sqrt()
    }

    /// Mean NEES over the samples where it is defined.
    pub fn mean_nees(&self) -> f64 {
        let defined = self.samples - self.nees_undefined;
        self.sum_nees / defined.max(1) as f64
    }
}

/// What the estimator keeps besides the filter.
#[derive(Clone, Debug, Default)]
pub(super) struct Estimating {
    pub accuracy: Accuracy,
    /// Camera frames seen, for race mode's every-k-th correction.
    pub camera_frames: u64,
    pub race_sigma_warned: bool,
    /// Marker IDs the filter must not correct with: blocks the mission moved.
    pub ignored_markers: Vec<u32>,
    /// The true pose given with this step, to score against.
    pub truth: Option<Pose2>,
}

/// The 95 % chi-square band of one NEES sample with 3 degrees of freedom.
pub const NEES_BAND_3DOF: (f64, f64) = (0.216, 9.348);

impl Pilot {
    pub(super) fn estimate_motion(&mut self, wheels: WheelTravel) {
        self.odometry.update(wheels);
        self.ekf.predict(wheels);
    }

    pub(super) fn estimate_sightings(&mut self, sightings: &[MarkerSighting]) {
        self.estimating.camera_frames += 1;
        let mut nearest;
        let mut used = sightings;
        if self.mode == Mode::Race {
            // Seed 001 race mode: "reduced SLAM updates". Every k-th frame and the nearest m
            // are navdeck's way of reducing them.
            let race = &self.settings.race;
            if !self
                .estimating
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
        let ignored = &self.estimating.ignored_markers;
        let added: Vec<u32> = (used.iter())
            .filter(|s| !ignored.contains(&s.id))
            .filter(|s| self.ekf.correct(**s) == Outcome::Added)
            .map(|s| s.id)
            .collect();
        for id in added {
            let category = navdeck_core::perception::markers::MarkerCategory::of(id);
            self.log(
                Level::Info,
                format!("new landmark {id} ({})", category.label()),
            );
        }
    }

    /// The position's standard deviation along its worst direction, metres.
    pub(super) fn position_std(&self) -> f64 {
        let c = self.pose_covariance();
        navdeck_core::slam::ellipse::axes(&c.fixed_view::<2, 2>(0, 0).into_owned(), 1.0).0
    }

    /// In race mode, warns once when the position's uncertainty passes the bound.
    pub(super) fn check_race_uncertainty(&mut self) {
        let major = self.position_std();
        let bound = self.settings.race.sigma_warning;
        if self.mode == Mode::Race && major > bound && !self.estimating.race_sigma_warned {
            self.estimating.race_sigma_warned = true;
            self.log(
                Level::Warn,
                format!("race: position uncertainty {major:.3} m is past {bound:.3} m; slow down"),
            );
        } else if major <= bound {
            self.estimating.race_sigma_warned = false;
        }
    }

    /// One accuracy sample against the truth, when it is known.
    pub(super) fn sample_accuracy(&mut self) {
        if let Some(truth) = self.estimating.truth {
            let cov = self.pose_covariance();
            let est = self.pose();
            self.estimating.accuracy.add(truth, est, &cov);
        }
    }

    /// How well the estimate tracked the truth (empty without a simulator).
    pub fn accuracy(&self) -> &Accuracy {
        &self.estimating.accuracy
    }

    /// Standard deviations of the pose estimate: x, y (m) and heading (rad).
    pub fn pose_sigma(&self) -> (f64, f64, f64) {
        let c = self.pose_covariance();
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
        // The worst sample is 0.1 m off; the RMSE averages it with a perfect one.
        assert!((a.position_max_error() - 0.1).abs() < 1e-12);
        assert!(a.position_max_error() >= a.position_rmse());
        // Each sample's NEES is 1.
        assert!((a.mean_nees() - 1.0).abs() < 1e-9);
    }
}
