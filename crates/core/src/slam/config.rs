//! `[slam]`: the EKF's noise and landmark settings (seed 001 "Robot Configuration").

use serde::{Deserialize, Serialize};

/// EKF-SLAM noise and landmark management (seed 001 `ekf_slam` and "Landmark Management").
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SlamConfig {
    /// Wheel rotation noise, degrees per revolution of the wheel (seed 001 `motor_std`: 4,
    /// "degrees"; per revolution is navdeck's reading).
    pub motor_std_deg: f64,
    /// Range noise, metres (seed 001 `dist_std`: 0.1).
    pub dist_std: f64,
    /// Bearing noise, degrees (seed 001 `angle_std`: 4).
    pub angle_std_deg: f64,
    /// Sightings of an ID before it enters the state (seed 001: "1+").
    pub min_sightings: u32,
    /// `Some(v)`: new landmarks start with variance v m^2 and no correlation (seed 001: 0.5);
    /// `None`: the uncertainty is propagated through the inverse observation model.
    pub fixed_initial_variance: Option<f64>,
    /// Mahalanobis gate on a sighting's innovation, chi-square with 2 degrees of freedom
    /// (13.82 rejects 0.1 % of good sightings).
    pub gate_chi2: f64,
}

impl Default for SlamConfig {
    fn default() -> Self {
        Self {
            motor_std_deg: 4.0,
            dist_std: 0.1,
            angle_std_deg: 4.0,
            min_sightings: 1,
            fixed_initial_variance: None,
            gate_chi2: 13.82,
        }
    }
}

impl SlamConfig {
    /// Checks what the parser cannot.
    pub fn validate(&self) -> Result<(), crate::data::check::Invalid> {
        use crate::data::check;
        check::within(&[
            ("motor_std_deg", self.motor_std_deg, 0.0, 90.0),
            ("dist_std", self.dist_std, 0.0001, 10.0),
            ("angle_std_deg", self.angle_std_deg, 0.01, 90.0),
            ("gate_chi2", self.gate_chi2, 0.1, 1000.0),
        ])?;
        if let Some(v) = self.fixed_initial_variance {
            check::within(&[("fixed_initial_variance", v, 1e-6, 100.0)])?;
        }
        check::counts_within(&[("min_sightings", u64::from(self.min_sightings), 1, 1000)])
    }
}
