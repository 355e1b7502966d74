//! Line-of-sight shortcutting (seed 002, A* + ray tracing): from the end point, test whether
//! the straight line to point 1 is free; if not, to point 2, and so on; the first free one
//! becomes the new end point, until the start is reached. The exact start and goal replace
//! the first and last cell centres (seed 002: a cell centre is not accurate enough).

use super::astar::SearchOptions;
use super::segment_cells::for_each_cell;
use crate::geometry::Point2;
use crate::map::costmap::Costmap;

/// Shortcuts the waypoints `cells[keep[k]]` of an A* cell path.
///
/// A straight line may replace a stretch of the path only if every cell it touches may be
/// entered and none costs more than the worst cell of the stretch it replaces, so a shortcut
/// never takes the robot nearer an obstacle than the search chose to go (a line through
/// inflated cells is allowed only where the path already went through cells that costly,
/// e.g. starting beside a wall). The start cell is exempt: the robot is already there.
///
/// `keep` lists indices into `cells`, ascending, from 0 to the last (see
/// [`simplify`](super::simplify::simplify)); the result starts at `start` and ends at `goal`.
pub fn shortcut(
    map: &Costmap,
    cells: &[(usize, usize)],
    keep: &[usize],
    start: Point2,
    goal: Point2,
    options: &SearchOptions,
) -> Vec<Point2> {
    let point = |k: usize| waypoint(map, cells, keep[k], start, goal);
    if keep.len() <= 1 {
        return dedup(vec![start, goal]);
    }
    let start_cell = cells[0];
    let cost_of = |c: (usize, usize)| options.traversal_cost(map.get(c.0, c.1));
    let worst_between = |a: usize, b: usize| {
        cells[keep[a]..=keep[b]]
            .iter()
            .filter_map(|&c| cost_of(c))
            .max()
            .unwrap_or(0)
    };
    let line_ok = |a: usize, b: usize| {
        let worst = worst_between(a, b);
        for_each_cell(map, point(a), point(b), |x, y| {
            (x, y) == start_cell || cost_of((x, y)).is_some_and(|c| c <= worst)
        })
    };
    let mut chosen = vec![keep.len() - 1];
    let mut end = keep.len() - 1;
    while end > 0 {
        // The point just before `end` is always acceptable: it is the searched path itself.
        let next = (0..end - 1).find(|&k| line_ok(k, end)).unwrap_or(end - 1);
        chosen.push(next);
        end = next;
    }
    chosen.reverse();
    dedup(chosen.into_iter().map(point).collect())
}

/// The world position of path cell `i`: the exact start or goal at the ends, else its centre.
pub fn waypoint(
    map: &Costmap,
    cells: &[(usize, usize)],
    i: usize,
    start: Point2,
    goal: Point2,
) -> Point2 {
    if i + 1 == cells.len() {
        goal
    } else if i == 0 {
        start
    } else {
        map.center_of(cells[i].0, cells[i].1)
    }
}

/// Drops consecutive repeats (start and goal in one cell, for instance).
fn dedup(mut points: Vec<Point2>) -> Vec<Point2> {
    points.dedup();
    points
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::costmap::{INFLATED, LETHAL};

    fn straight_l(map: &Costmap) -> Vec<Point2> {
        // An L around nothing: right along row 1, then up column 8.
        let cells: Vec<_> = (1..=8)
            .map(|x| (x, 1))
            .chain((2..=8).map(|y| (8, y)))
            .collect();
        let keep = vec![0, 7, cells.len() - 1];
        let (s, g) = (map.center_of(1, 1), map.center_of(8, 8));
        shortcut(map, &cells, &keep, s, g, &SearchOptions::default())
    }

    #[test]
    fn an_l_in_open_space_becomes_one_straight_line() {
        let map = Costmap::new(10, 10, 0.1, Point2::new(0.0, 0.0), 0);
        assert_eq!(straight_l(&map).len(), 2);
    }

    #[test]
    fn the_corner_stays_when_the_line_would_cross_a_wall_or_inflation() {
        for blocker in [LETHAL, INFLATED] {
            let mut map = Costmap::new(10, 10, 0.1, Point2::new(0.0, 0.0), 0);
            map.set(5, 4, blocker);
            assert_eq!(straight_l(&map).len(), 3, "blocker cost {blocker}");
        }
    }
}
