//! Grids and reference searches shared by the planning tests and the A* benchmark.
#![allow(dead_code)]

use navdeck::geometry::Point2;
use navdeck::map::costmap::{Costmap, INFLATED, LETHAL};
use navdeck::plan::SearchOptions;
use navdeck::plan::astar::{CARDINAL, DIAGONAL, octile};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Obstacles of the benchmark arena, in cells: (x0, y0, x1, y1) inclusive.
const BLOCKS: [(usize, usize, usize, usize); 6] = [
    (100, 0, 105, 300),
    (200, 100, 205, 399),
    (300, 0, 305, 280),
    (140, 320, 170, 350),
    (240, 40, 270, 70),
    (330, 330, 370, 360),
];

/// A 4 m square at 1 cm: three long walls and three boxes, each with a 5-cell inflated ring
/// (cost 70) and a gradient falling from 69 to 0 over the next 15 cells. Deterministic.
pub fn arena() -> Costmap {
    let mut map = Costmap::new(400, 400, 0.01, Point2::new(0.0, 0.0), 0);
    for y in 0..400 {
        for x in 0..400 {
            let d = BLOCKS
                .iter()
                .map(|&(x0, y0, x1, y1)| {
                    let dx = x0.saturating_sub(x).max(x.saturating_sub(x1)) as f64;
                    let dy = y0.saturating_sub(y).max(y.saturating_sub(y1)) as f64;
                    dx.hypot(dy)
                })
                .fold(f64::INFINITY, f64::min);
            let cost = if d == 0.0 {
                LETHAL
            } else if d <= 5.0 {
                INFLATED
            } else if d < 20.0 {
                (69.0 * (20.0 - d) / 15.0) as u8
            } else {
                0
            };
            map.set(x, y, cost);
        }
    }
    map
}

/// A small random grid: some lethal cells, some unknown, costs scattered over 0..=99.
/// A cell anywhere on `map`.
pub fn random_cell(rng: &mut ChaCha8Rng, map: &Costmap) -> (usize, usize) {
    (
        rng.random_range(0..map.width),
        rng.random_range(0..map.height),
    )
}

pub fn random_grid(rng: &mut ChaCha8Rng) -> Costmap {
    let (w, h) = (rng.random_range(2..16), rng.random_range(2..16));
    let mut map = Costmap::new(w, h, 0.1, Point2::new(-0.5, 0.25), 0);
    for c in map.cost.iter_mut() {
        let r: f64 = rng.random();
        *c = if r < 0.25 {
            LETHAL + rng.random_range(0..3) * 50 // 100, 150 or 200: all lethal
        } else if r < 0.3 {
            255
        } else if r < 0.6 {
            rng.random_range(0..100)
        } else {
            0
        };
    }
    map
}

/// Whether a cell may be entered and at what penalty, per the rules A* promises.
fn penalty(map: &Costmap, options: &SearchOptions, x: usize, y: usize) -> Option<u32> {
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

/// A plain Dijkstra over the same moves: the cheapest cost, or None if the goal is blocked
/// or unreachable.
pub fn dijkstra(
    map: &Costmap,
    options: &SearchOptions,
    start: (usize, usize),
    goal: (usize, usize),
) -> Option<u64> {
    penalty(map, options, goal.0, goal.1)?;
    let mut best = vec![u64::MAX; map.width * map.height];
    let mut queue = BinaryHeap::new();
    best[map.index(start.0, start.1)] = 0;
    queue.push(Reverse((0u64, start)));
    while let Some(Reverse((d, (x, y)))) = queue.pop() {
        if (x, y) == goal {
            return Some(d);
        }
        if d > best[map.index(x, y)] {
            continue;
        }
        for ((nx, ny), c) in moves(map, options, x, y) {
            let nd = d + u64::from(c);
            let j = map.index(nx, ny);
            if nd < best[j] {
                best[j] = nd;
                queue.push(Reverse((nd, (nx, ny))));
            }
        }
    }
    None
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
