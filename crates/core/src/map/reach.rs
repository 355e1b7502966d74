//! Where a plan may start and end on a costmap: out of the lethal ring around a robot
//! pressed against a wall, short of a landmark it should face, and near a goal that lies
//! in an obstacle (Nav2's goal tolerance).

use super::costmap::{Costmap, INFLATED, is_lethal};
use crate::geometry::Point2;
use std::borrow::Cow;

/// A copy of the map in which the lethal ring around the robot's own position is made
/// merely inflated, so a robot standing close to a wall can still plan its way out.
pub fn escape_map(map: &Costmap, start: Point2, radius: f64) -> Cow<'_, Costmap> {
    if !map
        .cell_of(start)
        .is_some_and(|(x, y)| is_lethal(map.get(x, y)))
    {
        return Cow::Borrowed(map);
    }
    let mut copy = map.clone();
    let r = (radius / map.resolution).ceil() as i64;
    if let Some((cx, cy)) = map.cell_of(start) {
        for dy in -r..=r {
            for dx in -r..=r {
                let (x, y) = (cx as i64 + dx, cy as i64 + dy);
                if dx * dx + dy * dy > r * r || x < 0 || y < 0 {
                    continue;
                }
                let (x, y) = (x as usize, y as usize);
                if x < map.width && y < map.height && is_lethal(map.get(x, y)) {
                    copy.set(x, y, INFLATED + 29);
                }
            }
        }
    }
    Cow::Owned(copy)
}

/// Where the robot goes to reach a landmark: on the line from `marker` towards `robot`, the
/// first point at least `approach` away that a plan may enter, then `margin` further.
pub fn approach_point(
    map: &Costmap,
    marker: Point2,
    robot: Point2,
    approach: f64,
    margin: f64,
) -> Point2 {
    let d = marker.distance(robot);
    if d < 1e-9 {
        return marker;
    }
    let (ux, uy) = ((robot.x - marker.x) / d, (robot.y - marker.y) / d);
    let along = |s: f64| Point2::new(marker.x + ux * s, marker.y + uy * s);
    let mut s = approach;
    while s < d {
        if !is_lethal(map.at(along(s))) {
            return along((s + margin).min(d));
        }
        s += map.resolution;
    }
    robot
}

/// `p` itself if a plan may end there, else the nearest such point within `reach` metres
/// (searched ring by ring, 32 directions a ring), like Nav2's goal tolerance.
pub fn nearest_passable(map: &Costmap, p: Point2, reach: f64) -> Option<Point2> {
    if !is_lethal(map.at(p)) {
        return Some(p);
    }
    let mut r = map.resolution;
    while r <= reach {
        let found = (0..32)
            .map(|k| f64::from(k) * std::f64::consts::TAU / 32.0)
            .map(|a| Point2::new(p.x + r * a.cos(), p.y + r * a.sin()))
            .find(|q| map.cell_of(*q).is_some() && !is_lethal(map.at(*q)));
        if found.is_some() {
            return found;
        }
        r += map.resolution;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::costmap::{FREE, LETHAL};

    /// A 2 m x 1 m map at 0.1 m, free but for a lethal wall at x in [1.0, 1.1).
    fn walled() -> Costmap {
        let mut map = Costmap::new(20, 10, 0.1, Point2::new(0.0, 0.0), FREE);
        for y in 0..10 {
            map.set(10, y, LETHAL);
        }
        map
    }

    #[test]
    fn escape_map_clears_only_the_ring_around_a_robot_in_lethal_space() {
        let map = walled();
        assert!(matches!(
            escape_map(&map, Point2::new(0.35, 0.55), 0.2),
            Cow::Borrowed(_)
        ));
        let out = escape_map(&map, Point2::new(1.05, 0.55), 0.2);
        // The wall cell under the robot and its neighbours within 2 cells are passable...
        assert!(!is_lethal(out.at(Point2::new(1.05, 0.55))));
        assert!(!is_lethal(out.at(Point2::new(1.05, 0.35))));
        assert!(out.at(Point2::new(1.05, 0.55)) >= INFLATED);
        // ...and the wall beyond the ring is not.
        assert!(is_lethal(out.at(Point2::new(1.05, 0.05))));
    }

    #[test]
    fn approach_point_stops_short_of_the_marker_on_the_robot_side() {
        let map = walled();
        // Marker in the wall, robot 0.8 m to its left: the first passable point at least
        // 0.2 m out is 0.2 m away (x = 0.85), then 0.05 m further.
        let p = approach_point(
            &map,
            Point2::new(1.05, 0.55),
            Point2::new(0.25, 0.55),
            0.2,
            0.05,
        );
        assert!(
            (p.x - 0.8).abs() < 1e-9 && (p.y - 0.55).abs() < 1e-9,
            "{p:?}"
        );
        // A robot already inside the approach distance stays where it is.
        let close = Point2::new(0.95, 0.55);
        assert_eq!(
            approach_point(&map, Point2::new(1.05, 0.55), close, 0.2, 0.05),
            close
        );
    }

    #[test]
    fn nearest_passable_moves_a_goal_out_of_an_obstacle_within_reach() {
        let map = walled();
        let free = Point2::new(0.5, 0.5);
        assert_eq!(nearest_passable(&map, free, 0.3), Some(free));
        let goal = Point2::new(1.05, 0.55);
        let moved = nearest_passable(&map, goal, 0.3).expect("a passable point");
        assert!(!is_lethal(map.at(moved)));
        assert!(moved.distance(goal) <= 0.1 + 1e-9, "{moved:?}");
        // Nothing passable within reach: no goal.
        let mut solid = Costmap::new(10, 10, 0.1, Point2::new(0.0, 0.0), LETHAL);
        solid.set(0, 0, FREE);
        assert_eq!(nearest_passable(&solid, Point2::new(0.55, 0.55), 0.2), None);
    }
}
