//! One call from start and goal to a timed trajectory: A*, simplification, shortcutting,
//! smoothing and the velocity profile, each step behind its config switch.

use super::astar::{AStar, SearchOptions};
use super::config::PlanConfig;
use super::error::PlanError;
use super::profile::{ProfileLimits, profile};
use super::shortcut::{shortcut, waypoint};
use super::simplify::simplify;
use super::smooth::{Smoothing, linear, smooth_checked};
use super::trajectory::Trajectory;
use crate::geometry::Point2;
use crate::map::costmap::Costmap;

/// A finished plan.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// The A* path as cell centres.
    pub cells: Vec<Point2>,
    /// After simplification and shortcutting, from the exact start to the exact goal.
    pub waypoints: Vec<Point2>,
    /// After smoothing and the velocity profile.
    pub trajectory: Trajectory,
    /// Cost of the A* path in cell units (a cardinal step is 1.0).
    pub cost: f64,
    /// Arc length of the trajectory, metres.
    pub length: f64,
    /// Cells A* expanded.
    pub expanded: usize,
    /// How the trajectory's samples were made.
    pub smoothing: Smoothing,
}

/// A reusable planner: owns the search buffers.
#[derive(Debug, Default)]
pub struct Planner {
    search: AStar,
}

impl Planner {
    pub fn new() -> Self {
        Self::default()
    }

    /// Plans from `start` to `goal` (world positions, metres) on `map`.
    pub fn plan(
        &mut self,
        map: &Costmap,
        start: Point2,
        goal: Point2,
        config: &PlanConfig,
    ) -> Result<Plan, PlanError> {
        config
            .validate()
            .map_err(|(field, value, reason)| PlanError::InvalidConfig {
                field,
                value,
                reason,
            })?;
        let options = search_options(config);
        let cell = |which, p: Point2| {
            map.cell_of(p).ok_or(PlanError::OffMap {
                which,
                x: p.x,
                y: p.y,
            })
        };
        let (sc, gc) = (cell("start", start)?, cell("goal", goal)?);
        let found = self
            .search
            .search(map, sc, gc, &options)
            .map_err(|e| at_goal(e, goal))?;
        let cells = &found.cells;
        let keep: Vec<usize> = if config.simplify {
            simplify(cells)
        } else {
            (0..cells.len()).collect()
        };
        let waypoints = if config.shortcut {
            shortcut(map, cells, &keep, start, goal, &options)
        } else {
            let mut w: Vec<Point2> = keep
                .iter()
                .map(|&i| waypoint(map, cells, i, start, goal))
                .collect();
            w.dedup();
            w
        };
        let (samples, smoothing) = if config.smooth {
            smooth_checked(
                &waypoints,
                map,
                &options,
                config.control_spacing,
                config.sample_spacing,
            )
        } else {
            (linear(&waypoints, config.sample_spacing), Smoothing::Off)
        };
        let trajectory = profile(&samples, &profile_limits(config));
        Ok(Plan {
            cells: cells.iter().map(|&(x, y)| map.center_of(x, y)).collect(),
            waypoints,
            length: trajectory.length(),
            trajectory,
            cost: found.cost_cells(),
            expanded: found.expanded,
            smoothing,
        })
    }
}

/// The search options a config asks for.
pub fn search_options(config: &PlanConfig) -> SearchOptions {
    SearchOptions {
        allow_unknown: config.allow_unknown,
        unknown_cost: config.unknown_cost,
    }
}

/// The profile limits a config asks for, starting and ending at rest.
pub fn profile_limits(config: &PlanConfig) -> ProfileLimits {
    ProfileLimits {
        max_speed: config.max_speed,
        max_accel: config.max_accel,
        max_lateral_accel: config.max_lateral_accel,
        start_speed: 0.0,
        end_speed: 0.0,
    }
}

/// Names the goal as the user gave it rather than its cell centre.
fn at_goal(e: PlanError, goal: Point2) -> PlanError {
    let (x, y) = (goal.x, goal.y);
    match e {
        PlanError::GoalInObstacle { cost, .. } => PlanError::GoalInObstacle { x, y, cost },
        PlanError::GoalUnknown { .. } => PlanError::GoalUnknown { x, y },
        PlanError::Unreachable { expanded, .. } => PlanError::Unreachable { x, y, expanded },
        other => other,
    }
}
