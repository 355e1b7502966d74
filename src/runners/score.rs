//! The estimate and the map scored against the twin's truth, as `navdeck mission` and
//! `navdeck --headless` report them (flattened into their JSON).

use crate::map::truth::{WallAgreement, wall_agreement};
use crate::pilot::Pilot;
use crate::sim::GroundTruth;
use serde::Serialize;

/// How the pilot's estimate and map compare with the twin's truth; every figure `None`
/// without a twin.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct TruthScore {
    /// The absolute trajectory error, sampled every control period: its RMSE and its
    /// largest position error, metres, and its heading RMSE, degrees.
    pub position_rmse: Option<f64>,
    pub position_max_error: Option<f64>,
    pub heading_rmse_deg: Option<f64>,
    /// Mean normalised estimation error squared of the pose (3 degrees of freedom).
    pub mean_nees: Option<f64>,
    /// The map a user would save (`Pilot::map_to_save`: lidar SLAM's map when it runs,
    /// else the planning map) against the twin's walls and box outlines.
    pub map_vs_walls: Option<WallAgreement>,
}

impl TruthScore {
    /// The pilot's figures as they stand, when a twin knows the truth.
    pub fn of(pilot: &Pilot, twin: Option<&dyn GroundTruth>) -> TruthScore {
        let Some(twin) = twin else {
            return TruthScore::default();
        };
        let accuracy = pilot.accuracy();
        TruthScore {
            position_rmse: Some(accuracy.position_rmse()),
            position_max_error: Some(accuracy.position_max_error()),
            heading_rmse_deg: Some(accuracy.heading_rmse().to_degrees()),
            mean_nees: Some(accuracy.mean_nees()),
            map_vs_walls: Some(wall_agreement(&pilot.map_to_save(), &twin.world().walls)),
        }
    }

    /// One line for people: "RMSE 0.031 m, max 0.082 m, 1.20 deg; walls mapped 87 %,
    /// map on walls 92 %", or `None` without a twin.
    pub fn line(&self) -> Option<String> {
        let (rmse, max, heading) = (
            self.position_rmse?,
            self.position_max_error?,
            self.heading_rmse_deg?,
        );
        let mut out = format!("RMSE {rmse:.3} m, max {max:.3} m, {heading:.2} deg");
        if let Some(m) = &self.map_vs_walls {
            out += &format!(
                "; walls mapped {:.0} %, map on walls {:.0} %",
                m.wall_recall * 100.0,
                m.wall_precision * 100.0
            );
        }
        Some(out)
    }
}
