//! A loop: one corridor all the way round an island of walls, for measuring how far a
//! pose estimate drifts round a long loop before it comes back to where it started.

use super::draft::Draft;
use super::draw::pick;
use super::rules::{TRIES, WALL_CLEARANCE};
use crate::geometry::{Point2, Segment};
use crate::sim::World;
use crate::sim::shapes::rect_edges;
use rand_chacha::ChaCha8Rng;

/// Narrowest corridor, metres: a block `WALL_CLEARANCE` from both walls.
const MIN_WIDTH: f64 = 2.0 * WALL_CLEARANCE;
/// Widest corridor, metres: at 12 m x 6 m even four corridors this wide leave the loop
/// 30 m or more round (2 x (12 + 6) - 4 x 1.4 = 30.4).
const MAX_WIDTH: f64 = 1.4;
/// Smallest island side, metres: one 0.5 m marker spacing, so each of its walls carries a
/// marker away from its corners.
const MIN_ISLAND: f64 = 0.5;

/// Draws the four corridor widths (left, right, bottom, top) and closes the island
/// between them.
pub fn build(d: &mut Draft, rng: &mut ChaCha8Rng) -> Result<(), String> {
    let (hw, hh) = (d.world.width / 2.0, d.world.height / 2.0);
    for _ in 0..TRIES {
        let mut width = || pick(rng, MIN_WIDTH, MAX_WIDTH, 0.05);
        let (Some(left), Some(right), Some(bottom), Some(top)) =
            (width(), width(), width(), width())
        else {
            break;
        };
        let lo = Point2::new(-hw + left, -hh + bottom);
        let hi = Point2::new(hw - right, hh - top);
        if hi.x - lo.x >= MIN_ISLAND && hi.y - lo.y >= MIN_ISLAND {
            return d.add_island(lo, hi);
        }
    }
    Err(format!(
        "no room for an island {MIN_ISLAND} m across inside corridors {MIN_WIDTH}-{MAX_WIDTH} m wide"
    ))
}

/// The length of the corridor's centreline round the island, metres, when the world's
/// walls inside the boundary (box outlines aside) are one closed axis-aligned rectangle:
/// the rectangle midway between the boundary and the island, whose sides are half the sum
/// of the boundary's and the island's, so its perimeter is W + H + w + h.
pub fn centreline(world: &World) -> Option<f64> {
    let outlines: Vec<Segment> = (world.obstacles.iter())
        .flat_map(|o| rect_edges(o.pose, o.width, o.height))
        .collect();
    let same = |a: &Segment, b: &Segment| a.a.distance(b.a) < 1e-6 && a.b.distance(b.b) < 1e-6;
    let (hw, hh) = (world.width / 2.0, world.height / 2.0);
    let on_boundary = |s: &Segment| {
        let edge_x = |x: f64| (x.abs() - hw).abs() < 1e-6;
        let edge_y = |y: f64| (y.abs() - hh).abs() < 1e-6;
        (edge_x(s.a.x) && edge_x(s.b.x) && s.a.x == s.b.x)
            || (edge_y(s.a.y) && edge_y(s.b.y) && s.a.y == s.b.y)
    };
    let inner: Vec<&Segment> = (world.walls.iter())
        .filter(|s| !on_boundary(s) && !outlines.iter().any(|o| same(s, o)))
        .collect();
    if inner.len() != 4 {
        return None;
    }
    let xs = inner.iter().flat_map(|s| [s.a.x, s.b.x]);
    let ys = inner.iter().flat_map(|s| [s.a.y, s.b.y]);
    let (x0, x1) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    let (y0, y1) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    // Each side of the rectangle must be one of the walls.
    let sides = [
        ((x0, y0), (x0, y1)),
        ((x0, y1), (x1, y1)),
        ((x1, y1), (x1, y0)),
        ((x1, y0), (x0, y0)),
    ]
    .map(|(a, b)| Segment::new(Point2::new(a.0, a.1), Point2::new(b.0, b.1)));
    let reversed = |s: &Segment| Segment::new(s.b, s.a);
    let closed = sides.iter().all(|side| {
        inner
            .iter()
            .any(|w| same(w, side) || same(w, &reversed(side)))
    });
    let inside = x0 > -hw && x1 < hw && y0 > -hh && y1 < hh && x1 > x0 && y1 > y0;
    (closed && inside).then_some(world.width + world.height + (x1 - x0) + (y1 - y0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::generate::{GenerateOptions, Style, check_reachable, generate};
    use std::path::Path;

    fn loop_world(seed: u64, size: (f64, f64)) -> World {
        let options = GenerateOptions {
            seed,
            size: Some(size),
            style: Style::Loop,
            ..GenerateOptions::default()
        };
        generate(&options).unwrap_or_else(|e| panic!("{size:?} seed {seed}: {e}"))
    }

    #[test]
    fn a_loop_at_12_by_6_is_30_m_round_reachable_and_reads_back() {
        for seed in 1..=10 {
            let world = loop_world(seed, (12.0, 6.0));
            let length = centreline(&world).expect("a ring corridor");
            assert!(length >= 30.0, "seed {seed}: {length:.2} m round");
            check_reachable(&world).unwrap();
            let back = World::from_toml(&world.to_toml(), Path::new("loop")).unwrap();
            assert_eq!(back, world);
            assert_eq!(centreline(&back), Some(length));
        }
    }

    #[test]
    fn the_centreline_of_a_hand_made_ring() {
        // A 6 x 4 m world round a 3.6 x 1.6 m island (corridors 1.2 m wide): the
        // centreline is a 4.8 x 2.8 m rectangle, 15.2 m round.
        let world = loop_world(1, (6.0, 4.0));
        let mut ring = World {
            walls: world.walls[..4].to_vec(),
            obstacles: Vec::new(),
            track: None,
            ..world.clone()
        };
        let p = |x, y| Point2::new(x, y);
        let corners = [p(-1.8, -0.8), p(-1.8, 0.8), p(1.8, 0.8), p(1.8, -0.8)];
        for k in 0..4 {
            ring.walls
                .push(Segment::new(corners[k], corners[(k + 1) % 4]));
        }
        let length = centreline(&ring).unwrap();
        assert!((length - 15.2).abs() < 1e-9, "{length}");
        // A wall missing: no ring.
        ring.walls.pop();
        assert_eq!(centreline(&ring), None);
    }
}
