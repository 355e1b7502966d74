//! Why a plan could not be made; each variant names the offending value (printed short:
//! a goal at 1e308 m reads `1e308`, not 309 digits).

use crate::data::number::{fixed, short};

/// A planning failure.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PlanError {
    #[error("{which} ({}, {}) is off the map", fixed(*x, 3), fixed(*y, 3))]
    OffMap { which: &'static str, x: f64, y: f64 },
    #[error("goal ({}, {}) is inside an obstacle (cell cost {cost})", fixed(*x, 3), fixed(*y, 3))]
    GoalInObstacle { x: f64, y: f64, cost: u8 },
    #[error(
        "goal ({}, {}) lies in unexplored space and unknown cells are not allowed",
        fixed(*x, 3), fixed(*y, 3)
    )]
    GoalUnknown { x: f64, y: f64 },
    #[error("goal ({}, {}) is unreachable: searched {expanded} cells", fixed(*x, 3), fixed(*y, 3))]
    Unreachable { x: f64, y: f64, expanded: usize },
    #[error("plan.{field} = {}: {reason}", short(*value))]
    InvalidConfig {
        field: &'static str,
        value: f64,
        reason: std::borrow::Cow<'static, str>,
    },
}
