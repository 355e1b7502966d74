//! Which way a gate faces, from the map. Two markers 0.2 m apart, each first placed from a
//! single sighting with centimetres of noise, can tilt the line between them by tens of
//! degrees, and a drop place worked out from that line alone can land behind the wall. The
//! lidar maps the wall the gate is on to a centimetre, so the free space in front of the
//! gate says which way is in (navdeck's).

use crate::geometry::Point2;
use crate::map::costmap::{Costmap, LETHAL, NO_INFORMATION};

/// The free space is sampled on a circle this far from the gate's centre, metres: beyond
/// the lethal ring around the wall, within the drop staging distance.
const RING: f64 = 0.4;
/// Directions sampled on the circle.
const SAMPLES: usize = 72;
/// Fewer free samples than this say nothing (an unmapped gate).
const MIN_FREE: usize = 6;
/// The free directions must gather on one side: their mean resultant length (circular
/// statistics' R, |Σ u| / n) at least this. A wall with its half circle free gives 2/π ≈
/// 0.64; a wall the map shows free on both sides (scans folded in before the estimate
/// corrected a drift) gives about 0 and says nothing (navdeck's).
const MIN_RESULTANT: f64 = 0.3;
/// A marker line whose normal lies within this of the free side is trusted, radians
/// (30°): it is the finer of the two when the markers are well placed.
const AGREE: f64 = std::f64::consts::PI / 6.0;

/// The unit direction from `center` into the mapped free space around it (the mean of
/// the free directions on a circle), if enough of the circle is mapped free and the free
/// part lies to one side.
pub fn free_side(map: &Costmap, center: Point2) -> Option<(f64, f64)> {
    let (mut sx, mut sy, mut n) = (0.0, 0.0, 0);
    for k in 0..SAMPLES {
        let a = k as f64 * std::f64::consts::TAU / SAMPLES as f64;
        let (s, c) = a.sin_cos();
        let p = Point2::new(center.x + RING * c, center.y + RING * s);
        let inside = map.cell_of(p).is_some();
        let cost = map.at(p);
        if inside && cost < LETHAL && cost != NO_INFORMATION {
            sx += c;
            sy += s;
            n += 1;
        }
    }
    let len = sx.hypot(sy);
    let one_sided = n >= MIN_FREE && len >= MIN_RESULTANT * n as f64;
    one_sided.then(|| (sx / len, sy / len))
}

/// The gate's normal: the markers' line normal turned to the free side when the two
/// agree within 30°, the free side alone when they do not, and with no map around the
/// gate, the line normal turned towards `robot` (which sees the markers' faces).
pub fn gate_normal(map: &Costmap, a: Point2, b: Point2, robot: Point2) -> (f64, f64) {
    let center = Point2::new((a.x + b.x) / 2.0, (a.y + b.y) / 2.0);
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let len = dx.hypot(dy).max(1e-9);
    let mut normal = (-dy / len, dx / len);
    let free = free_side(map, center);
    let towards = free.unwrap_or((robot.x - center.x, robot.y - center.y));
    if normal.0 * towards.0 + normal.1 * towards.1 < 0.0 {
        normal = (-normal.0, -normal.1);
    }
    match free {
        Some(free) if normal.0 * free.0 + normal.1 * free.1 < AGREE.cos() => free,
        _ => normal,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::costmap::FREE;

    /// 3 m x 3 m at 2 cm: free above y = 0, a wall along y = 0 with its lethal ring,
    /// nothing known below.
    fn wall_map() -> Costmap {
        let mut map = Costmap::new(150, 150, 0.02, Point2::new(-1.5, -1.5), NO_INFORMATION);
        for y in 0..150 {
            for x in 0..150 {
                let wy = map.center_of(x, y).y;
                if wy >= 0.15 {
                    map.set(x, y, FREE);
                } else if wy >= -0.01 {
                    map.set(x, y, LETHAL);
                }
            }
        }
        map
    }

    #[test]
    fn markers_tilted_far_off_the_wall_still_give_a_gate_facing_the_free_side() {
        let map = wall_map();
        // Truly at (-0.1, 0) and (0.1, 0); estimated 60° off, with the robot far to the
        // right, so the line and the robot's side alone would point behind the wall.
        let (a, b) = (Point2::new(-0.05, 0.087), Point2::new(0.05, -0.087));
        let n = gate_normal(&map, a, b, Point2::new(2.0, 0.3));
        assert!(n.1 > 0.95, "into the room: {n:?}");
        // Well placed markers: their line's normal, turned into the room.
        let n = gate_normal(
            &map,
            Point2::new(0.1, 0.01),
            Point2::new(-0.1, -0.01),
            Point2::new(2.0, 0.3),
        );
        assert!((n.0 + 0.0995).abs() < 1e-3 && n.1 > 0.99, "{n:?}");
    }

    #[test]
    fn a_wall_mapped_free_on_both_sides_leaves_the_markers_to_decide() {
        // A drifted estimate folded scans in from both sides of the wall: free above and
        // below, with a few cells more free off to one side, which alone would have
        // turned the gate along its wall.
        let mut map = wall_map();
        for y in 0..150 {
            for x in 0..150 {
                let c = map.center_of(x, y);
                if c.y < -0.15 && c.x < 0.2 {
                    map.set(x, y, FREE);
                }
            }
        }
        assert!(free_side(&map, Point2::new(0.0, 0.0)).is_none());
        let n = gate_normal(
            &map,
            Point2::new(0.1, 0.01),
            Point2::new(-0.1, -0.01),
            Point2::new(0.5, 1.0),
        );
        assert!(n.1 > 0.99, "the markers' normal, towards the robot: {n:?}");
    }

    #[test]
    fn with_no_map_around_the_gate_the_robot_side_decides() {
        let map = Costmap::new(10, 10, 0.1, Point2::new(-0.5, -0.5), NO_INFORMATION);
        let n = gate_normal(
            &map,
            Point2::new(-0.1, 0.0),
            Point2::new(0.1, 0.0),
            Point2::new(0.0, -1.0),
        );
        assert!((n.1 + 1.0).abs() < 1e-9, "{n:?}");
        assert!(free_side(&map, Point2::new(0.0, 0.0)).is_none());
    }
}
