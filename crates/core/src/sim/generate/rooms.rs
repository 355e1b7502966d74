//! Rooms: the area split into 2-4 rooms by walls across, each wall with a doorway, so the
//! rooms form a tree joined by doors (a binary space partition: de Berg et al.,
//! Computational Geometry, 3rd ed., section 12.1). With loops, every wall long enough
//! gets a second doorway: two doors between the same rooms are a way round the wall
//! between them.

use super::draft::Draft;
use super::draw::pick;
use super::rules::{MARKER_END_CLEARANCE, MIN_PASSAGE, MIN_ROOM, TRIES};
use crate::geometry::Point2;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// Wall left either side of a doorway, metres (at least one marker's width and a half).
const MIN_PIECE: f64 = 0.25;
/// Widest doorway above `MIN_PASSAGE`, metres.
const DOOR_EXTRA: f64 = 0.3;
/// A wall meeting another keeps this far from its doorway, metres.
const DOOR_MARGIN: f64 = 0.3;
/// Wall left between two doorways, metres: a room's width, so the way round is a loop
/// through both rooms and not round a post.
const LOOP_PIECE: f64 = MIN_ROOM;

#[derive(Clone, Copy, Debug)]
struct Rect {
    x0: f64,
    y0: f64,
    x1: f64,
    y1: f64,
}

impl Rect {
    fn long_side(&self) -> f64 {
        (self.x1 - self.x0).max(self.y1 - self.y0)
    }

    fn area(&self) -> f64 {
        (self.x1 - self.x0) * (self.y1 - self.y0)
    }
}

/// Splits the draft's area into `rooms` rooms (2-4 drawn when `None`); with `loops`, at
/// least one wall has two doorways.
pub fn build(
    d: &mut Draft,
    rng: &mut ChaCha8Rng,
    loops: bool,
    rooms: Option<usize>,
) -> Result<(), String> {
    let (hw, hh) = (d.world.width / 2.0, d.world.height / 2.0);
    let drawn = rng.random_range(2..=4usize);
    let wanted = rooms.unwrap_or(drawn);
    let mut rooms = vec![Rect {
        x0: -hw,
        y0: -hh,
        x1: hw,
        y1: hh,
    }];
    while rooms.len() < wanted {
        let Some(k) = (0..rooms.len())
            .filter(|&k| rooms[k].long_side() >= 2.0 * MIN_ROOM)
            .max_by(|&a, &b| rooms[a].area().total_cmp(&rooms[b].area()))
        else {
            break;
        };
        let (a, b) = split(d, rng, rooms.remove(k), loops)?;
        rooms.extend([a, b]);
    }
    if rooms.len() < 2 {
        return Err("the area is too small to split into rooms".into());
    }
    if rooms.len() < wanted {
        return Err(format!(
            "only {} rooms of at least {MIN_ROOM} m fit where {wanted} were asked for",
            rooms.len()
        ));
    }
    // One doorway per wall but for each second one.
    if loops && d.doors.len() < rooms.len() {
        return Err(format!(
            "no wall between rooms long enough for two doorways {LOOP_PIECE} m apart"
        ));
    }
    Ok(())
}

/// A wall across `r`'s longer side with a doorway in it, and with `loops` a second one
/// where the wall is long enough; returns the two rooms.
fn split(
    d: &mut Draft,
    rng: &mut ChaCha8Rng,
    r: Rect,
    loops: bool,
) -> Result<(Rect, Rect), String> {
    let across_x = r.x1 - r.x0 >= r.y1 - r.y0;
    // (along the split axis, across it) -> world point.
    let point = |t: f64, s: f64| {
        if across_x {
            Point2::new(t, s)
        } else {
            Point2::new(s, t)
        }
    };
    let (t0, t1, s0, s1) = if across_x {
        (r.x0, r.x1, r.y0, r.y1)
    } else {
        (r.y0, r.y1, r.x0, r.x1)
    };
    for _ in 0..TRIES {
        let Some(t) = pick(rng, t0 + MIN_ROOM, t1 - MIN_ROOM, 0.05) else {
            break;
        };
        let (a, b) = (point(t, s0), point(t, s1));
        let ends_clear = [a, b].into_iter().all(|p| {
            d.marker_distance(p) >= MARKER_END_CLEARANCE && d.door_distance(p) >= DOOR_MARGIN
        });
        let Some(gaps) = doorways(rng, (s0, s1), loops, d.doorway) else {
            continue;
        };
        if !ends_clear {
            continue;
        }
        let mut from = a;
        for &(g0, g1) in &gaps {
            let (door_a, door_b) = (point(t, g0), point(t, g1));
            d.add_interior(from, door_a)?;
            d.doors.push(crate::geometry::Segment::new(door_a, door_b));
            from = door_b;
        }
        d.add_interior(from, b)?;
        let (lo, hi) = if across_x {
            (Rect { x1: t, ..r }, Rect { x0: t, ..r })
        } else {
            (Rect { y1: t, ..r }, Rect { y0: t, ..r })
        };
        return Ok((lo, hi));
    }
    Err(format!(
        "no place for a wall across the room [{}, {}] x [{}, {}] clear of markers and doorways",
        r.x0, r.x1, r.y0, r.y1
    ))
}

/// Doorways, as (start, end) along a wall spanning `s0..s1`, `MIN_PIECE` of wall at its
/// ends: one, or with `loops` two `LOOP_PIECE` apart where the wall is long enough; each
/// `width` wide, or drawn.
fn doorways(
    rng: &mut ChaCha8Rng,
    (s0, s1): (f64, f64),
    loops: bool,
    width: Option<f64>,
) -> Option<Vec<(f64, f64)>> {
    let mut door = || {
        let drawn = pick(rng, MIN_PASSAGE, MIN_PASSAGE + DOOR_EXTRA, 0.05);
        width.or(drawn)
    };
    let first = door()?;
    let second = if loops { door() } else { None };
    match second {
        Some(second) if s1 - s0 - 2.0 * MIN_PIECE - first - second >= LOOP_PIECE => {
            let last = s1 - MIN_PIECE - second - LOOP_PIECE - first;
            let at = pick(rng, s0 + MIN_PIECE, last, 0.05)?;
            let next = pick(rng, at + first + LOOP_PIECE, s1 - MIN_PIECE - second, 0.05)?;
            Some(vec![(at, at + first), (next, next + second)])
        }
        _ => {
            let at = pick(rng, s0 + MIN_PIECE, s1 - MIN_PIECE - first, 0.05)?;
            Some(vec![(at, at + first)])
        }
    }
}
