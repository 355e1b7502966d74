//! Why a plan could not be made; each variant names the offending value.

/// A planning failure.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PlanError {
    #[error("{which} ({x:.3}, {y:.3}) is off the map")]
    OffMap { which: &'static str, x: f64, y: f64 },
    #[error("goal ({x:.3}, {y:.3}) is inside an obstacle (cell cost {cost})")]
    GoalInObstacle { x: f64, y: f64, cost: u8 },
    #[error("goal ({x:.3}, {y:.3}) lies in unexplored space and unknown cells are not allowed")]
    GoalUnknown { x: f64, y: f64 },
    #[error("goal ({x:.3}, {y:.3}) is unreachable: searched {expanded} cells")]
    Unreachable { x: f64, y: f64, expanded: usize },
    #[error("plan.{field} = {value}: {reason}")]
    InvalidConfig {
        field: &'static str,
        value: f64,
        reason: std::borrow::Cow<'static, str>,
    },
}
