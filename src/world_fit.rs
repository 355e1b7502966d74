//! Whether a world suits the configured robot and map: checked when a session starts,
//! where both are known.

use crate::config::Config;
use crate::sim::World;

/// Most cells of the planning map a world may ask for (the same limit as `[map]`'s).
const MAX_MAP_CELLS: f64 = 16.0e6;

/// Whether `world` suits the robot and the map of `config`: its planning map within
/// `MAX_MAP_CELLS` at `[map] resolution`, and the robot's footprint at the start clear
/// of walls and blocks.
pub fn world_fits(world: &World, config: &Config) -> Result<(), String> {
    let res = config.map.resolution;
    let cells =
        (world.width.max(config.map.width) / res) * (world.height.max(config.map.height) / res);
    if cells > MAX_MAP_CELLS {
        return Err(format!(
            "size {} x {} m at [map] resolution {res} m makes {cells:.0} cells, over the limit of {MAX_MAP_CELLS:.0}: use a coarser resolution",
            world.width, world.height
        ));
    }
    let radius = config.robot.footprint_radius;
    let start = world.start.position();
    if !world.contains(start) || !(world.start.theta.is_finite()) {
        return Err(format!(
            "the start ({:.2}, {:.2}) lies outside the world, which spans {} x {} m about (0, 0)",
            start.x, start.y, world.width, world.height
        ));
    }
    for (i, o) in world.obstacles.iter().enumerate() {
        if crate::sim::shapes::rect_contains(o.pose, o.width, o.height, start) {
            return Err(format!(
                "the start ({:.2}, {:.2}) lies inside obstacles[{i}]",
                start.x, start.y
            ));
        }
    }
    if let Some(d) = world
        .walls
        .iter()
        .map(|w| w.distance_to(start))
        .find(|&d| d < radius)
    {
        return Err(format!(
            "the robot's footprint ([robot] footprint_radius {radius} m) at the start ({:.2}, {:.2}) reaches {:.3} m into a wall",
            start.x,
            start.y,
            radius - d
        ));
    }
    for (i, b) in world.blocks.iter().enumerate() {
        let edges = crate::sim::shapes::rect_edges(b.pose, b.size, b.size);
        if edges.iter().any(|e| e.distance_to(start) < radius) {
            return Err(format!(
                "the robot's footprint ([robot] footprint_radius {radius} m) at the start ({:.2}, {:.2}) overlaps blocks[{i}]",
                start.x, start.y
            ));
        }
    }
    Ok(())
}
