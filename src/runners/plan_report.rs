//! `navdeck plan`: one plan on a world file or a Nav2 map, printed for people or as JSON.

use crate::config::Config;
use crate::geometry::Point2;
use crate::map::belief::BeliefMap;
use crate::map::config::MapConfig;
use crate::plan::pipeline::Planner;
use crate::sim::World;
use serde::Serialize;

/// What to plan on.
#[derive(Clone, Debug)]
pub enum Terrain {
    /// A twin world, as a robot that has seen all of it would map it.
    World(World),
    /// A Nav2 map: its grid, at its own resolution.
    Map(crate::map::grid::OccupancyGrid),
}

/// The outcome of `navdeck plan`.
#[derive(Clone, Debug, Serialize)]
pub struct PlanReport {
    pub from: Point2,
    pub to: Point2,
    /// Path length, metres, after post-processing; cost of the A* path in cells.
    pub length: f64,
    pub cost: f64,
    pub expanded: usize,
    pub waypoints: Vec<Point2>,
    /// The timed trajectory: x, y, v (m/s), t (s), every `sample_every` samples.
    pub trajectory: Vec<[f64; 4]>,
    pub duration: f64,
    /// The sharpest turn on the smoothed path, 1/m (seed 004 section A's kappa).
    pub max_curvature: f64,
    /// Filled in by the caller, which owns the clock.
    pub planning_time_ms: Option<f64>,
}

/// The costmap a robot would plan on after seeing the whole terrain.
pub fn survey(terrain: &Terrain, config: &MapConfig) -> BeliefMap {
    match terrain {
        Terrain::World(world) => {
            let extent = (
                world.width.max(config.width),
                world.height.max(config.height),
            );
            let mut map = BeliefMap::new(config, extent);
            map.update_landmarks(world.markers.iter().map(|m| (m.id, m.position)));
            map.absorb_grid(&world.rasterize(config.resolution));
            map
        }
        Terrain::Map(grid) => {
            let config = MapConfig {
                resolution: grid.resolution,
                ..config.clone()
            };
            let mut map = BeliefMap::covering(&config, grid.origin, grid.extent());
            map.absorb_grid(grid);
            map
        }
    }
}

/// Plans on `map` from `from` to `to` with the config's `[plan]` settings.
pub fn plan(
    map: &BeliefMap,
    from: Point2,
    to: Point2,
    config: &Config,
) -> Result<PlanReport, crate::plan::error::PlanError> {
    let plan = Planner::new().plan(map.costmap(), from, to, &config.plan)?;
    let points = &plan.trajectory.points;
    // About a sample every 5 cm is plenty for a person or a plot.
    let every = (points.len() / 200).max(5);
    let mut trajectory: Vec<[f64; 4]> = points
        .iter()
        .step_by(every)
        .map(|p| [p.position.x, p.position.y, p.v, p.t])
        .collect();
    if let Some(last) = points.last()
        && points.len() % every != 1
    {
        trajectory.push([last.position.x, last.position.y, last.v, last.t]);
    }
    Ok(PlanReport {
        from,
        to,
        length: plan.length,
        cost: plan.cost,
        expanded: plan.expanded,
        waypoints: plan.waypoints.clone(),
        duration: plan.trajectory.duration(),
        max_curvature: points.iter().map(|p| p.curvature.abs()).fold(0.0, f64::max),
        trajectory,
        planning_time_ms: None,
    })
}

/// The report as a person reads it.
pub fn human(r: &PlanReport) -> String {
    let mut out = format!(
        "path from ({:.2}, {:.2}) to ({:.2}, {:.2}): {:.2} m, cost {:.1}, {} cells expanded\n",
        r.from.x, r.from.y, r.to.x, r.to.y, r.length, r.cost, r.expanded
    );
    out += &format!(
        "drives in {:.1} s at the profile's speeds; sharpest turn {:.2} 1/m\n",
        r.duration, r.max_curvature
    );
    if let Some(ms) = r.planning_time_ms {
        out += &format!("planned in {ms:.2} ms\n");
    }
    out += "waypoints:\n";
    for p in &r.waypoints {
        out += &format!("  {:7.3} {:7.3}\n", p.x, p.y);
    }
    out
}
