//! Worlds generated from a seed, for measuring the mission on arenas it has never seen
//! (issue "Autonomy in any world").
//!
//! A candidate is drawn from a `ChaCha8Rng` seeded with the seed: the boundary with its
//! markers, the style's interior walls (`rooms.rs`, `corridors.rs`, `ring.rs`), both gates on the
//! boundary (`gates.rs`), the boxes (`boxes.rs`), the blocks and the start (`blocks.rs`).
//! It is written as a world file and read back with the loader, so the file is known to
//! load, and the world read back must pass the reachability check (`reach.rs`). A candidate
//! that fails is followed by the next drawn from the same generator, up to `ATTEMPTS`:
//! the same options always give the same world. Without wall markers, the candidate is
//! drawn with them and they are taken off at the end, so the layout is the same.
//!
//! Track worlds (`Style::Track`, `track.rs`) are drawn their own way: a walled room with
//! a closed lane, its lights and barriers and a start on it, and no blocks, gates or
//! markers; they are read back the same way and must pass `track_check` instead.

mod blocks;
mod boxes;
mod corridors;
mod draft;
mod draw;
mod gates;
mod options;
mod reach;
mod ring;
mod rooms;
mod rules;
#[cfg(test)]
mod tests;
mod track;
pub mod track_check;
mod track_shape;
#[cfg(test)]
mod track_tests;

pub use options::{Colours, GenerateError, GenerateOptions, Style};
pub use reach::check as check_reachable;
pub use ring::centreline as loop_centreline;

use crate::geometry::wrap_angle;
use crate::perception::markers::MarkerCategory;
use crate::sim::{BlockColor, World};
use draft::Draft;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rules::ATTEMPTS;
use std::path::Path;

/// A world for `options`: the same options always give the same world.
pub fn generate(options: &GenerateOptions) -> Result<World, GenerateError> {
    options.validate()?;
    if options.style == Style::Track {
        return track::generate(options);
    }
    let mut rng = ChaCha8Rng::seed_from_u64(options.seed);
    let mut reason = String::new();
    for _ in 0..ATTEMPTS {
        let drafted = match candidate(options, &mut rng) {
            Ok(world) => world,
            Err(why) => {
                reason = why;
                continue;
            }
        };
        let world = read_back(options, &drafted)?;
        match check_reachable(&world) {
            Ok(()) => return Ok(world),
            Err(why) => reason = why,
        }
    }
    Err(GenerateError::Exhausted {
        seed: options.seed,
        style: options.style,
        attempts: ATTEMPTS,
        reason,
    })
}

/// One candidate world, or why it could not be finished.
fn candidate(options: &GenerateOptions, rng: &mut ChaCha8Rng) -> Result<World, String> {
    let (w, h) = options.size();
    let mut d = Draft::new(options.name(), w, h, options.marker_spacing);
    d.doorway = options.doorway;
    match options.style {
        Style::Boxes => {}
        Style::Rooms => rooms::build(&mut d, rng, options.loops, options.rooms)?,
        Style::Corridors => corridors::build(&mut d, rng, options.loops)?,
        Style::Loop => ring::build(&mut d, rng)?,
        Style::Track => return Err("a track world is drawn by track.rs".into()),
    }
    let colours = options.colours.draw(options.blocks, rng);
    gates::place(&mut d, rng, &colours)?;
    boxes::place(&mut d, rng, options.obstacles)?;
    blocks::place(&mut d, rng, &colours)?;
    blocks::start(&mut d, rng)?;
    let mut world = d.world;
    if !options.wall_markers {
        // Gate markers stay (the mission delivers to them); block markers ride with
        // their blocks and are not in this list.
        world.markers.retain(|m| {
            !matches!(
                MarkerCategory::of(m.id),
                MarkerCategory::Boundary | MarkerCategory::Obstacle
            )
        });
    }
    Ok(world)
}

/// The candidate written as a world file and read back by the loader, which checks every
/// rule a hand-written file must keep; it must come back as the same world.
fn read_back(options: &GenerateOptions, drafted: &World) -> Result<World, GenerateError> {
    let unloadable = |reason: String| GenerateError::Unloadable {
        seed: options.seed,
        style: options.style,
        reason,
    };
    let text = drafted.to_toml();
    let world = World::from_toml(&text, Path::new(&options.name()))
        .map_err(|e| unloadable(e.to_string()))?;
    same(drafted, &world).map_err(unloadable)?;
    Ok(world)
}

/// Differences beyond the file's rounding between the drafted and the loaded world.
fn same(a: &World, b: &World) -> Result<(), String> {
    const CLOSE: f64 = 1e-6;
    let counts = |w: &World| {
        (
            w.walls.len(),
            w.markers.len(),
            w.obstacles.len(),
            w.gates.len(),
            w.blocks.len(),
        )
    };
    if counts(a) != counts(b) {
        return Err(format!(
            "(walls, markers, obstacles, gates, blocks) {:?} became {:?}",
            counts(a),
            counts(b)
        ));
    }
    let segment_moved = a.walls.iter().any(|s| {
        !b.walls
            .iter()
            .any(|t| s.a.distance(t.a) < CLOSE && s.b.distance(t.b) < CLOSE)
    });
    let marker_moved = a.markers.iter().any(|m| {
        b.marker(m.id).is_none_or(|n| {
            m.position.distance(n.position) > CLOSE || wrap_angle(m.normal - n.normal).abs() > CLOSE
        })
    });
    let block_moved = a.blocks.iter().zip(&b.blocks).any(|(p, q)| {
        p.markers != q.markers || p.pose.position().distance(q.pose.position()) > CLOSE
    });
    let start_moved = a.start.position().distance(b.start.position()) > CLOSE
        || wrap_angle(a.start.theta - b.start.theta).abs() > CLOSE;
    match () {
        _ if segment_moved => Err("a wall moved".into()),
        _ if marker_moved => Err("a marker moved".into()),
        _ if block_moved => Err("a block moved".into()),
        _ if start_moved => Err("the start moved".into()),
        _ if a.gates != b.gates => Err("the gates changed".into()),
        _ if a.track != b.track => Err("the track changed".into()),
        _ => Ok(()),
    }
}

/// One line on a world's contents: size, boxes, interior walls, blocks, gates, wall
/// markers, and a ring corridor's length round its centreline; or a track world's lane.
pub fn describe(world: &World) -> String {
    if let Some(scene) = &world.track {
        return format!(
            "{}, {} m x {} m, a lane {:.1} m round, {} m wide, tightest bend {:.2} m, {} lights and {} barriers, start ({}, {})",
            world.name,
            world.width,
            world.height,
            scene.track.length(),
            scene.track.lane_width,
            scene.track.min_radius(track_check::RADIUS_WINDOW),
            scene.lights.len(),
            scene.barriers.len(),
            world.start.x,
            world.start.y,
        );
    }
    let count = |c: BlockColor| world.blocks.iter().filter(|b| b.color == c).count();
    let outlines = 4 * world.obstacles.len();
    // Boundary: the four sides of the rectangle; the rest are interior walls.
    let interior = world.walls.len().saturating_sub(outlines + 4);
    let gates: Vec<&str> = world.gates.iter().map(|g| g.color.label()).collect();
    let wall_markers = (world.markers.iter())
        .filter(|m| {
            matches!(
                MarkerCategory::of(m.id),
                MarkerCategory::Boundary | MarkerCategory::Obstacle
            )
        })
        .count();
    let ring = loop_centreline(world).map_or(String::new(), |length| {
        format!(", a corridor {length:.1} m round its centreline")
    });
    format!(
        "{}, {} m x {} m, {} boxes, {} interior walls{ring}, {} blocks ({} red, {} blue), gates: {}, {wall_markers} wall and box markers, start ({}, {})",
        world.name,
        world.width,
        world.height,
        world.obstacles.len(),
        interior,
        world.blocks.len(),
        count(BlockColor::Red),
        count(BlockColor::Blue),
        gates.join(" and "),
        world.start.x,
        world.start.y,
    )
}
