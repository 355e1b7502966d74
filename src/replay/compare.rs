//! How a re-run compares with its recording: each control tick's estimate against the
//! recorded one, bit for bit, and both against the recorded truth (a twin's).

use crate::app::App;
use crate::geometry::{Pose2, wrap_angle};
use crate::msgs::picture;
use crate::record::encode;
use crate::record::recorded::Recorded;
use serde::Serialize;

/// How a re-run compares with the recording, so far.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Comparison {
    /// Control ticks compared, and those whose estimate (pose and covariance) is the
    /// recorded one bit for bit.
    pub ticks: usize,
    pub identical: usize,
    /// The largest distance between the re-run's position and the recorded one, metres.
    pub max_position_difference: f64,
    /// Both estimates against the recorded truth (a twin's): RMSE in metres and degrees.
    pub recorded_position_rmse: Option<f64>,
    pub recorded_heading_rmse_deg: Option<f64>,
    pub rerun_position_rmse: Option<f64>,
    pub rerun_heading_rmse_deg: Option<f64>,
    /// The estimator each used.
    pub recorded_estimator: String,
    pub rerun_estimator: String,
}

/// Squared errors summed: the recorded estimate's and the re-run's, (position, heading).
#[derive(Clone, Debug, Default)]
struct Errors {
    n: usize,
    recorded: (f64, f64),
    rerun: (f64, f64),
}

/// A re-run's comparison as it goes.
#[derive(Clone, Debug, Default)]
pub struct Comparer {
    next_estimate: usize,
    comparison: Comparison,
    errors: Errors,
}

impl Comparer {
    pub fn new(recorded_estimator: String, rerun_estimator: String) -> Self {
        Self {
            comparison: Comparison {
                recorded_estimator,
                rerun_estimator,
                ..Comparison::default()
            },
            ..Self::default()
        }
    }

    /// Compares the ticks `app` has made since the last call with `recorded`'s.
    pub fn take(&mut self, app: &mut App, recorded: &Recorded) {
        for (t, pose, cov) in app.take_tick_estimates() {
            let Some(was) = recorded.estimates.get(self.next_estimate) else {
                continue;
            };
            if (was.time - t).abs() > 1e-6 {
                continue;
            }
            self.next_estimate += 1;
            let c = &mut self.comparison;
            c.ticks += 1;
            let mine = encode(&picture::pose_with_covariance(pose, &cov, was.stamp, "map"));
            if mine == was.bytes {
                c.identical += 1;
            }
            let gap = pose.position().distance(was.pose.position());
            c.max_position_difference = c.max_position_difference.max(gap);
            if let Some(truth) = recorded.truth_at(t) {
                let truth = truth.pose();
                let e = &mut self.errors;
                e.n += 1;
                add_error(&mut e.recorded, was.pose, truth);
                add_error(&mut e.rerun, pose, truth);
            }
        }
    }

    /// How the re-run compares so far.
    pub fn comparison(&self) -> Comparison {
        let mut c = self.comparison.clone();
        let e = &self.errors;
        if e.n > 0 {
            let n = e.n as f64;
            c.recorded_position_rmse = Some((e.recorded.0 / n).sqrt());
            c.recorded_heading_rmse_deg = Some((e.recorded.1 / n).sqrt().to_degrees());
            c.rerun_position_rmse = Some((e.rerun.0 / n).sqrt());
            c.rerun_heading_rmse_deg = Some((e.rerun.1 / n).sqrt().to_degrees());
        }
        c
    }
}

/// Adds the squared position and heading errors of `estimate` against `truth`.
fn add_error(sums: &mut (f64, f64), estimate: Pose2, truth: Pose2) {
    sums.0 += estimate.position().distance(truth.position()).powi(2);
    sums.1 += wrap_angle(estimate.theta - truth.theta).powi(2);
}
