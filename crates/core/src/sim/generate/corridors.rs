//! Corridors: 1-3 long walls along the world's longer side, each joined to one end wall
//! and leaving a turn at the other, alternately, so the corridors run as one winding way.
//! With loops, some walls (at least one) are free at both ends, a way round each.

use super::draft::Draft;
use super::draw::pick;
use super::rules::{MARKER_END_CLEARANCE, MIN_PASSAGE, TRIES};
use crate::geometry::Point2;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// Corridors are about this wide before jitter, metres: room for a block 0.5 m from both
/// walls and a little more.
const TYPICAL_WIDTH: f64 = 1.3;
/// Most long walls (each takes up to 96 boundary ids at the 12 m largest side).
const MAX_WALLS: usize = 3;
/// A wall moves up to this far off its even spacing, metres.
const JITTER: f64 = 0.15;
/// Widest turn at a wall's free end above `MIN_PASSAGE`, metres.
const TURN_EXTRA: f64 = 0.4;

/// How often a wall other than the one sure to be free is free at both ends with loops:
/// as likely as not, so loops and winding ways mix.
const BOTH_ENDS_FREE: f64 = 0.5;

/// Adds the long walls.
pub fn build(d: &mut Draft, rng: &mut ChaCha8Rng, loops: bool) -> Result<(), String> {
    let (w, h) = (d.world.width, d.world.height);
    let along_x = w >= h;
    let (long, cross) = if along_x { (w, h) } else { (h, w) };
    // (along the corridors, across them) -> world point.
    let point = |u: f64, v: f64| {
        if along_x {
            Point2::new(u, v)
        } else {
            Point2::new(v, u)
        }
    };
    let count = ((cross / TYPICAL_WIDTH).round() as usize)
        .saturating_sub(1)
        .clamp(1, MAX_WALLS);
    let spacing = cross / (count + 1) as f64;
    'candidate: for _ in 0..TRIES {
        let mut walls = Vec::with_capacity(count);
        let mut last = -cross / 2.0;
        let mut attach_low = rng.random_bool(0.5);
        // With loops, this wall (1-based) is free at both ends, and others may be.
        let free_wall = if loops {
            rng.random_range(1..=count)
        } else {
            0
        };
        for k in 1..=count {
            let even = -cross / 2.0 + k as f64 * spacing;
            let Some(v) = pick(rng, even - JITTER, even + JITTER, 0.05) else {
                continue 'candidate;
            };
            let drawn = pick(rng, MIN_PASSAGE, MIN_PASSAGE + TURN_EXTRA, 0.05);
            let Some(turn) = d.doorway.or(drawn) else {
                continue 'candidate;
            };
            if v - last < MIN_PASSAGE {
                continue 'candidate;
            }
            last = v;
            let (fixed, free) = if attach_low {
                (-long / 2.0, long / 2.0 - turn)
            } else {
                (long / 2.0, -long / 2.0 + turn)
            };
            let both_free = loops && (k == free_wall || rng.random_bool(BOTH_ENDS_FREE));
            if both_free {
                // A turn at the other end too: the wall stands alone.
                let drawn = pick(rng, MIN_PASSAGE, MIN_PASSAGE + TURN_EXTRA, 0.05);
                let Some(other) = d.doorway.or(drawn) else {
                    continue 'candidate;
                };
                let end = fixed - fixed.signum() * other;
                walls.push((point(end, v), point(free, v)));
                continue;
            }
            attach_low = !attach_low;
            let (a, b) = (point(fixed, v), point(free, v));
            if d.marker_distance(a) < MARKER_END_CLEARANCE {
                continue 'candidate;
            }
            walls.push((a, b));
        }
        if cross / 2.0 - last < MIN_PASSAGE {
            continue;
        }
        for (a, b) in walls {
            d.add_interior(a, b)?;
        }
        return Ok(());
    }
    Err(format!(
        "no place for {count} corridor walls {MIN_PASSAGE} m apart clear of the boundary markers"
    ))
}
