//! Whether a world suits the configured robot and map: checked when a session starts,
//! where both are known.

use crate::config::Config;
use crate::geometry::Pose2;
use crate::sim::World;

/// Whether `world` suits the robot and the map of `config`: its planning map within
/// `map::config::MAX_CELLS` at `[map] resolution`, and the robot's footprint at the start clear
/// of walls, obstacles and blocks.
pub fn world_fits(world: &World, config: &Config) -> Result<(), String> {
    config
        .map
        .check_extent((world.width, world.height))
        .map_err(|why| format!("size {why}"))?;
    pose_fits(
        world,
        world.start,
        config.robot.footprint_radius,
        "the start",
    )
}

/// Whether a robot of footprint `radius` can stand at `pose` in `world`: inside it and
/// clear of walls, obstacles and blocks. The one check for the start (`--start`, a world's
/// own) and for anywhere the twin's robot is put (`tour --kidnap`); `what` names the pose.
pub fn pose_fits(world: &World, pose: Pose2, radius: f64, what: &str) -> Result<(), String> {
    let p = pose.position();
    let short = |v: f64| {
        if v.abs() < 1e6 {
            format!("{v:.2}")
        } else {
            format!("{v:e}")
        }
    };
    let (x, y) = (short(p.x), short(p.y));
    if !world.contains(p) || !(pose.theta.is_finite()) {
        return Err(format!(
            "{what} ({x}, {y}) lies outside the world, which spans {:?} x {:?} m about (0, 0)",
            world.width, world.height
        ));
    }
    if world.width < 2.0 * radius || world.height < 2.0 * radius {
        return Err(format!(
            "the world, {:?} x {:?} m, is too small for the robot's footprint ([robot] \
             footprint_radius {radius} m)",
            world.width, world.height
        ));
    }
    if let Some(why) = world.pose_conflict(p, radius) {
        return Err(format!(
            "the robot's footprint ([robot] footprint_radius {radius} m) at {what} ({x}, {y}) {why}"
        ));
    }
    Ok(())
}
