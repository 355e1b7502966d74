//! Where to explore next: seed 001's furthest-valid-marker rule, or the nearest frontier
//! between known free space and unknown space (Yamauchi, "A frontier-based approach for
//! autonomous exploration", CIRA 1997).

use super::clusters::{clusters, nearest_centroid};
use crate::geometry::Point2;
use crate::map::costmap::{Costmap, INFLATED, NO_INFORMATION, is_lethal};
use crate::map::reach::nearest_passable;
use crate::perception::markers::MarkerCategory;
use std::collections::{BTreeMap, VecDeque};

/// Seed 001 "Marker Selection Heuristic": markers whose nearest neighbour is further than
/// this are isolated and ignored, metres.
pub const ISOLATED: f64 = 2.0;
/// How far from a robot standing in a lethal cell its flood may start, metres.
const START_REACH: f64 = 0.3;
/// Seed 001: markers closer to the robot than this are ignored, metres.
pub const TOO_CLOSE: f64 = 0.3;

/// The furthest boundary or obstacle marker from `robot` that is neither isolated, too
/// close, nor already `visited` (seed 001 `get_furthest_marker`).
pub fn furthest_marker(
    landmarks: &BTreeMap<u32, Point2>,
    robot: Point2,
    visited: &[u32],
) -> Option<(u32, Point2)> {
    let candidates: Vec<(u32, Point2)> = landmarks
        .iter()
        .filter(|&(&id, _)| {
            matches!(
                MarkerCategory::of(id),
                MarkerCategory::Boundary | MarkerCategory::Obstacle
            )
        })
        .map(|(&id, &p)| (id, p))
        .collect();
    candidates
        .iter()
        .filter(|(id, _)| !visited.contains(id))
        .filter(|(id, p)| {
            let nearest = candidates
                .iter()
                .filter(|(other, _)| other != id)
                .map(|(_, q)| p.distance(*q))
                .fold(f64::INFINITY, f64::min);
            nearest <= ISOLATED
        })
        .filter(|(_, p)| p.distance(robot) >= TOO_CLOSE)
        .max_by(|a, b| a.1.distance(robot).total_cmp(&b.1.distance(robot)))
        .copied()
}

/// A connected run of frontier cells.
#[derive(Clone, Debug, PartialEq)]
pub struct Frontier {
    /// The frontier cell nearest the cluster's centroid: a reachable place to go.
    pub target: Point2,
    pub cells: usize,
}

/// The cells the robot at `from` can reach through known, not lethal cells (4-connected),
/// starting from the nearest such cell within `START_REACH` when it stands in a lethal one.
pub fn reachable(map: &Costmap, from: Point2) -> Vec<bool> {
    let (w, h) = (map.width, map.height);
    let mut reach = vec![false; w * h];
    let open = |c: u8| c != NO_INFORMATION && !is_lethal(c);
    let start = nearest_passable(map, from, START_REACH).and_then(|p| map.cell_of(p));
    let Some((sx, sy)) = start.filter(|&(x, y)| open(map.get(x, y))) else {
        return reach;
    };
    let mut queue = VecDeque::from([(sx, sy)]);
    reach[sy * w + sx] = true;
    while let Some((x, y)) = queue.pop_front() {
        let next = [
            (x.wrapping_sub(1), y),
            (x + 1, y),
            (x, y.wrapping_sub(1)),
            (x, y + 1),
        ];
        for (nx, ny) in next {
            if nx < w && ny < h && !reach[ny * w + nx] && open(map.get(nx, ny)) {
                reach[ny * w + nx] = true;
                queue.push_back((nx, ny));
            }
        }
    }
    reach
}

/// Frontier clusters of at least `min_cells` cells among those `reach` marks (from
/// `reachable`): known cells below the 0.7 ring that touch an unknown cell, grouped
/// 8-connected. A frontier beyond a wall, or one only unknown space leads to, is no place
/// to go. An unknown cell that `known_elsewhere` says is known (another robot of a
/// fleet mapped it) makes no frontier.
pub fn frontiers(
    map: &Costmap,
    reach: &[bool],
    min_cells: usize,
    known_elsewhere: impl Fn(Point2) -> bool,
) -> Vec<Frontier> {
    let (w, h) = (map.width, map.height);
    let passable = |c: u8| c < INFLATED;
    let is_frontier = |x: usize, y: usize| {
        let c = map.get(x, y);
        if c == NO_INFORMATION || !passable(c) || !reach[y * w + x] {
            return false;
        }
        let unknown = |nx: usize, ny: usize| {
            map.get(nx, ny) == NO_INFORMATION && !known_elsewhere(map.center_of(nx, ny))
        };
        (x > 0 && unknown(x - 1, y))
            || (x + 1 < w && unknown(x + 1, y))
            || (y > 0 && unknown(x, y - 1))
            || (y + 1 < h && unknown(x, y + 1))
    };
    (clusters(w, h, is_frontier).into_iter())
        .filter(|cluster| cluster.len() >= min_cells)
        .filter_map(|cluster| {
            let (tx, ty) = nearest_centroid(&cluster, |_| true)?;
            Some(Frontier {
                target: map.center_of(tx, ty),
                cells: cluster.len(),
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::costmap::{FREE, LETHAL};

    #[test]
    fn the_furthest_marker_skips_isolated_close_and_visited_ones() {
        let marks: BTreeMap<u32, Point2> = [
            (1, Point2::new(0.1, 0.0)),   // too close
            (2, Point2::new(1.0, 0.0)),   // a valid neighbour of 3
            (3, Point2::new(2.0, 0.0)),   // the furthest valid one
            (301, Point2::new(9.0, 9.0)), // isolated
            (421, Point2::new(3.0, 0.0)), // a block: not a waypoint
        ]
        .into_iter()
        .collect();
        let robot = Point2::new(0.0, 0.0);
        assert_eq!(furthest_marker(&marks, robot, &[]).map(|m| m.0), Some(3));
        assert_eq!(furthest_marker(&marks, robot, &[3]).map(|m| m.0), Some(2));
    }

    #[test]
    fn frontiers_lie_between_free_and_unknown_cells() {
        // 20 x 10 cells: free on the left, unknown on the right, one wall cell.
        let mut map = Costmap::new(20, 10, 0.1, Point2::new(0.0, 0.0), NO_INFORMATION);
        for y in 0..10 {
            for x in 0..8 {
                map.set(x, y, FREE);
            }
        }
        map.set(7, 0, LETHAL);
        let robot = Point2::new(0.25, 0.55);
        let found = frontiers(&map, &reachable(&map, robot), 3, |_| false);
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!(found[0].cells, 9, "the lethal cell is no frontier");
        assert!((found[0].target.x - 0.75).abs() < 1e-9);
        assert!(
            frontiers(&map, &reachable(&map, robot), 10, |_| false).is_empty(),
            "too small a cluster"
        );
    }

    /// A walled room of known free cells in unknown space, 30 x 30 cells at 0.1 m: walls
    /// at x, y = 5 and 24; inside free, outside free in a strip beyond the east wall too.
    fn walled_room() -> Costmap {
        let mut map = Costmap::new(40, 30, 0.1, Point2::new(0.0, 0.0), NO_INFORMATION);
        for y in 5..=24 {
            for x in 5..=24 {
                let wall = x == 5 || x == 24 || y == 5 || y == 24;
                map.set(x, y, if wall { LETHAL } else { FREE });
            }
            // A strip seen through nothing: known free beyond the wall, next to unknown.
            for x in 26..30 {
                map.set(x, y, FREE);
            }
        }
        map
    }

    #[test]
    fn a_frontier_beyond_the_walls_is_no_target() {
        let map = walled_room();
        let inside = Point2::new(1.45, 1.45);
        assert!(
            frontiers(&map, &reachable(&map, inside), 3, |_| false).is_empty(),
            "the room is closed"
        );
        let reach = reachable(&map, inside);
        assert!(!reach[map.index(27, 10)], "the strip is beyond the wall");
        assert!(reach[map.index(10, 10)]);
    }

    #[test]
    fn a_doorway_makes_the_space_beyond_reachable() {
        let mut map = walled_room();
        // A door in the east wall and a corridor to the strip.
        for y in 12..16 {
            map.set(24, y, FREE);
            map.set(25, y, FREE);
        }
        let inside = Point2::new(1.45, 1.45);
        let found = frontiers(&map, &reachable(&map, inside), 3, |_| false);
        assert!(!found.is_empty());
        assert!(found.iter().all(|f| f.target.x > 2.5), "{found:?}");
    }

    #[test]
    fn a_robot_standing_in_a_lethal_cell_still_floods_from_beside_it() {
        let map = walled_room();
        // On the wall itself (as a robot pressed against it appears on the map).
        let reach = reachable(&map, Point2::new(0.55, 1.45));
        assert!(reach[map.index(10, 10)]);
    }
}
