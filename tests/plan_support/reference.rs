//! The moves A* promises, and the `pathfinding` crate's A* over them: the reference
//! navdeck's own search is held against.

use navdeck::map::costmap::Costmap;
use navdeck::plan::SearchOptions;
use navdeck::plan::astar::{CARDINAL, DIAGONAL, octile};

/// Whether a cell may be entered and at what penalty, per the rules A* promises.
pub fn penalty(map: &Costmap, options: &SearchOptions, x: usize, y: usize) -> Option<u32> {
    options
        .traversal_cost(map.get(x, y))
        .map(|c| 50 * u32::from(c))
}

/// The moves out of cell (x, y) with their integer costs: 8-connected, no corner cutting
/// between two blocked cardinal neighbours.
pub fn moves(
    map: &Costmap,
    options: &SearchOptions,
    x: usize,
    y: usize,
) -> Vec<((usize, usize), u32)> {
    let mut out = Vec::with_capacity(8);
    for dy in -1i64..=1 {
        for dx in -1i64..=1 {
            if dx == 0 && dy == 0 {
                continue;
            }
            let (nx, ny) = (x as i64 + dx, y as i64 + dy);
            if nx < 0 || ny < 0 || nx >= map.width as i64 || ny >= map.height as i64 {
                continue;
            }
            let (nx, ny) = (nx as usize, ny as usize);
            let Some(p) = penalty(map, options, nx, ny) else {
                continue;
            };
            let diagonal = dx != 0 && dy != 0;
            if diagonal
                && penalty(map, options, nx, y).is_none()
                && penalty(map, options, x, ny).is_none()
            {
                continue;
            }
            out.push(((nx, ny), if diagonal { DIAGONAL } else { CARDINAL } + p));
        }
    }
    out
}

/// The `pathfinding` crate's A* over the same moves and the same octile heuristic.
pub fn pathfinding_astar(
    map: &Costmap,
    options: &SearchOptions,
    start: (usize, usize),
    goal: (usize, usize),
) -> Option<(Vec<(usize, usize)>, u32)> {
    pathfinding::directed::astar::astar(
        &start,
        |&(x, y)| moves(map, options, x, y),
        |&(x, y)| octile(x.abs_diff(goal.0) as u32, y.abs_diff(goal.1) as u32),
        |&c| c == goal,
    )
}
