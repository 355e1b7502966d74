//! Whether a world suits the configured robot and map: checked when a session starts,
//! where both are known.

use crate::config::Config;
use crate::map::config::MAX_CELLS;
use crate::sim::World;

/// Whether `world` suits the robot and the map of `config`: its planning map within
/// `MAX_CELLS` at `[map] resolution`, and the robot's footprint at the start clear
/// of walls, obstacles and blocks.
pub fn world_fits(world: &World, config: &Config) -> Result<(), String> {
    let res = config.map.resolution;
    let cells =
        (world.width.max(config.map.width) / res) * (world.height.max(config.map.height) / res);
    if cells > MAX_CELLS {
        return Err(format!(
            "size {} x {} m at [map] resolution {res} m makes {cells:.0} cells, over the limit of {MAX_CELLS:.0}: use a coarser resolution",
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
    if let Some(why) = world.start_conflict(radius) {
        return Err(format!(
            "the robot's footprint ([robot] footprint_radius {radius} m) at the start ({:.2}, {:.2}) {why}",
            start.x, start.y
        ));
    }
    Ok(())
}
