//! What a runner reports of the estimator that placed the robot: its name and, when lidar
//! SLAM ran, the pose graph it built (keyframes, loop closures, and the closures the
//! twin's truth contradicts). Flattened into the mission's and the headless run's JSON.

use crate::pilot::Pilot;
use serde::Serialize;

/// One run's estimator figures; the counts are null when lidar SLAM did not run.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct EstimatorFigures {
    /// The estimator's name as `--estimator` takes it: "ekf", "mcl" or "slam".
    pub estimator: String,
    pub keyframes: Option<usize>,
    /// Loops closed this run (a continued map's saved ones not counted).
    pub loop_closures: Option<usize>,
    /// Loops closed that the twin's truth contradicts (0 without a twin).
    pub false_loop_closures: Option<usize>,
    /// MCL's status at the end: "localised", "localising: 3 hypotheses" or "lost: ...".
    pub localisation: Option<String>,
}

impl EstimatorFigures {
    pub fn of(pilot: &Pilot) -> Self {
        let slam = pilot.lidar_slam();
        EstimatorFigures {
            estimator: name(pilot),
            keyframes: slam.map(|s| s.slam.graph().poses.len()),
            loop_closures: slam.map(|s| s.closures.len()),
            false_loop_closures: slam.map(|s| s.false_closures()),
            localisation: pilot.mcl().map(|m| m.status().summary()),
        }
    }
}

/// The estimator that places the robot, as `--estimator` names it.
fn name(pilot: &Pilot) -> String {
    let name = if pilot.lidar_slam().is_some() {
        "slam"
    } else if pilot.mcl().is_some() {
        "mcl"
    } else {
        "ekf"
    };
    name.to_string()
}

/// A sweep's estimator figures: the loop closures of every run added up.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct SweepEstimatorFigures {
    /// The runs' estimator ("mixed" if they differ; none for no runs).
    pub estimator: Option<String>,
    pub loop_closures: Option<usize>,
    pub false_loop_closures: Option<usize>,
}

impl SweepEstimatorFigures {
    pub fn of<'a>(runs: impl Iterator<Item = &'a EstimatorFigures> + Clone) -> Self {
        let mut names = runs.clone().map(|r| r.estimator.as_str());
        let first = names.next();
        let estimator = first.map(|f| match names.all(|n| n == f) {
            true => f.to_string(),
            false => "mixed".to_string(),
        });
        let sum = |counts: Vec<Option<usize>>| counts.iter().copied().sum::<Option<usize>>();
        SweepEstimatorFigures {
            estimator,
            loop_closures: sum(runs.clone().map(|r| r.loop_closures).collect()),
            false_loop_closures: sum(runs.map(|r| r.false_loop_closures).collect()),
        }
    }
}
