//! The twin's world for a tag map (navdeck's, the seed has no simulator): a floor round
//! the tags with a wall a metre and a half beyond the farthest, the robot on the dock
//! with the camera's image centre over it, and a box on each edge asked for.

use super::drive::over_point;
use super::file::{TagId, TagMap};
use crate::sim::World;
use std::path::Path;

/// The wall stands this far beyond the farthest tag, metres.
const WALL_MARGIN: f64 = 1.5;
/// A box on an edge is this wide and deep, metres.
const BOX_SIZE: f64 = 0.15;

/// The world for `map`, the camera's image centre `look` metres ahead of the robot's
/// centre, and a box in the middle of each edge of `obstacles` (as (from, to)).
pub fn world_for(map: &TagMap, look: f64, obstacles: &[(TagId, TagId)]) -> Result<World, String> {
    let xs = map.tags.values().map(|t| t.x);
    let ys = map.tags.values().map(|t| t.y);
    let reach = xs.chain(ys).fold(0.0f64, |m, v| m.max(v.abs())) + WALL_MARGIN;
    let dock = map
        .tags
        .get(&map.dock)
        .ok_or_else(|| format!("the map has no dock tag {}", map.dock))?;
    let start = over_point(dock.x, dock.y, dock.zone.heading(), look);
    let mut text = format!(
        "name = \"tags\"\nsize = [{s}, {s}]\nstart = [{sx}, {sy}, {h}]\n\
         [[walls]]\npoints = [[-{r}, -{r}], [{r}, -{r}], [{r}, {r}], [-{r}, {r}]]\nclosed = true\n",
        s = 2.0 * reach + 0.2,
        r = reach,
        sx = start.x,
        sy = start.y,
        h = start.theta.to_degrees()
    );
    for (a, b) in obstacles {
        let joined = map.edge(*a, *b).or(map.edge(*b, *a)).is_some();
        let (Some(a), Some(b), true) = (map.tags.get(a), map.tags.get(b), joined) else {
            return Err(format!("no edge {a}-{b} in the map to put a box on"));
        };
        text.push_str(&format!(
            "[[obstacles]]\ncenter = [{}, {}]\nsize = [{BOX_SIZE}, {BOX_SIZE}]\n",
            (a.x + b.x) / 2.0,
            (a.y + b.y) / 2.0
        ));
    }
    World::from_toml(&text, Path::new("tags")).map_err(|e| e.to_string())
}
