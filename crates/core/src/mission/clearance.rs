//! How far the robot can drive straight ahead before the lidar's map has something in the
//! way. The drop at a gate creeps in until the gate's centre, placed from two markers, is
//! `drop_distance` away; a gate placed a few centimetres behind its wall would have the
//! robot push into the wall. The wall itself is mapped to a centimetre (navdeck's).

use crate::geometry::{Point2, Pose2};
use crate::map::costmap::Costmap;

/// Half the width of the band looked along, metres: narrower than the body, so a block
/// already delivered in the next drop place (0.12 m along) is not in the way.
pub(crate) const BAND: f64 = 0.05;
/// Nearer than this to the robot centre, the held block may be mapped: not looked at,
/// metres (the jaws hold a block's far face 0.14 m ahead).
const HELD_ZONE: f64 = 0.16;

/// The distance from the robot centre to the nearest occupied cell in the band ahead of
/// `pose`, looking from `HELD_ZONE` up to `max` metres; `None` when the band is clear or
/// there is no lidar map.
pub fn clear_ahead(map: &Costmap, occupied: &[bool], pose: Pose2, max: f64) -> Option<f64> {
    if occupied.len() != map.width * map.height {
        return None;
    }
    let (s, c) = pose.theta.sin_cos();
    let step = map.resolution / 2.0;
    let across = (BAND / step).ceil() as i64;
    let steps = ((max - HELD_ZONE) / step).ceil().max(0.0) as usize;
    (0..=steps).map(|i| HELD_ZONE + i as f64 * step).find(|&d| {
        (-across..=across).any(|j| {
            let side = j as f64 * step;
            let p = Point2::new(pose.x + d * c - side * s, pose.y + d * s + side * c);
            map.cell_of(p)
                .is_some_and(|(x, y)| occupied[map.index(x, y)])
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::costmap::FREE;

    #[test]
    fn the_wall_ahead_is_found_and_what_is_beside_or_held_is_not() {
        let map = Costmap::new(100, 100, 0.01, Point2::new(0.0, 0.0), FREE);
        let mut occupied = vec![false; 100 * 100];
        // A wall along x = 0.8 m, a delivered block 0.2 m aside, a held block 0.12 m ahead.
        for y in 0..100 {
            occupied[y * 100 + 80] = true;
        }
        occupied[70 * 100 + 70] = true;
        occupied[50 * 100 + 62] = true;
        let pose = Pose2::new(0.5, 0.5, 0.0);
        let d = clear_ahead(&map, &occupied, pose, 0.6).unwrap();
        assert!((d - 0.3).abs() < 0.01, "{d}");
        assert!(
            clear_ahead(&map, &occupied, pose, 0.25).is_none(),
            "beyond max"
        );
        let facing_away = Pose2::new(0.5, 0.5, std::f64::consts::PI);
        assert!(clear_ahead(&map, &occupied, facing_away, 0.45).is_none());
        assert!(clear_ahead(&map, &[], pose, 0.6).is_none(), "no lidar");
    }
}
