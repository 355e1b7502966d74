//! The `[plan]` config section: which post-processing steps run and the profile's limits.

use crate::map::costmap::LETHAL;
use serde::{Deserialize, Serialize};

/// Planning parameters (seeds 001, 002 and 004).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PlanConfig {
    /// Drop the A* path's collinear cells (seed 001 "Path Simplification").
    pub simplify: bool,
    /// Replace stretches of the path by straight lines of sight (seed 002).
    pub shortcut: bool,
    /// Round the corners with a cubic B-spline (seed 004 section A).
    pub smooth: bool,
    /// Whether unexplored cells may be planned through.
    pub allow_unknown: bool,
    /// The cost an unexplored cell counts as, 0..=99 (on seed 001's 0.0-1.0 scale, x 100).
    pub unknown_cost: u8,
    /// Distance between the spline's control points, metres.
    pub control_spacing: f64,
    /// Distance between trajectory samples, metres (seed 004: 400 points, about 0.01 m for 4 m).
    pub sample_spacing: f64,
    /// Top speed, m/s (navdeck's following speed; seed 004 uses 0.22).
    pub max_speed: f64,
    /// Acceleration and deceleration limit, m/s^2 (seed 004: 0.6).
    pub max_accel: f64,
    /// Lateral acceleration limit in turns, m/s^2 (seed 004: 0.9).
    pub max_lateral_accel: f64,
}

impl Default for PlanConfig {
    fn default() -> Self {
        Self {
            simplify: true,
            shortcut: true,
            smooth: true,
            allow_unknown: true,
            unknown_cost: 0,
            control_spacing: 0.1,
            sample_spacing: 0.01,
            max_speed: 0.2,
            max_accel: 0.6,
            max_lateral_accel: 0.9,
        }
    }
}

impl PlanConfig {
    /// Checks values a parser cannot: (field, value, reason) for the first bad one.
    pub fn validate(&self) -> Result<(), crate::data::check::Invalid> {
        crate::data::check::within(&[
            ("control_spacing", self.control_spacing, 0.01, 5.0),
            ("sample_spacing", self.sample_spacing, 0.001, 1.0),
            ("max_speed", self.max_speed, 0.001, 5.0),
            ("max_accel", self.max_accel, 0.01, 20.0),
            ("max_lateral_accel", self.max_lateral_accel, 0.01, 20.0),
        ])?;
        if self.unknown_cost >= LETHAL {
            return Err((
                "unknown_cost",
                f64::from(self.unknown_cost),
                "must be below 100 (lethal)".into(),
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_a_bad_value_is_named() {
        assert_eq!(PlanConfig::default().validate(), Ok(()));
        let c = PlanConfig {
            max_accel: -1.0,
            ..PlanConfig::default()
        };
        assert_eq!(
            c.validate(),
            Err(("max_accel", -1.0, "must lie in 0.01..=20".into()))
        );
        let c = PlanConfig {
            unknown_cost: 100,
            ..PlanConfig::default()
        };
        assert_eq!(c.validate().unwrap_err().0, "unknown_cost");
    }

    #[test]
    fn an_unknown_field_is_refused() {
        assert!(toml::from_str::<PlanConfig>("max_sped = 0.3").is_err());
        let c: PlanConfig = toml::from_str("smooth = false").unwrap();
        assert!(!c.smooth && c.shortcut);
    }
}
