//! Generated tag grids, to test tag driving on layouts no one drew: a grid of tags at
//! uneven spacings (random columns and rows), every neighbour joined both ways, some
//! joins left out (never cutting a tag off), the dock before the first column, tasks
//! through random tags and back, and in some grids a box standing on an edge a task
//! drives, so the robot must find its way round.

use super::file::{TagId, TagMap};
use super::graph::Blocked;
use rand::seq::IndexedRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write;

/// A generated grid: its map, and the edges with a box on them.
#[derive(Clone, Debug)]
pub struct TagGrid {
    pub map: TagMap,
    pub obstacles: Vec<(TagId, TagId)>,
    /// The map's text, as a file would hold it.
    pub text: String,
}

/// The dock's id, as seed 003 names it.
const DOCK: TagId = 508;

/// Whether every tag is reached from the dock along `edges`.
fn connected(tags: &BTreeMap<TagId, (f64, f64)>, edges: &BTreeSet<(TagId, TagId)>) -> bool {
    let reached = pathfinding::directed::bfs::bfs_reach(DOCK, |&at| {
        (edges.iter())
            .filter(move |e| e.0 == at)
            .map(|e| e.1)
            .collect::<Vec<_>>()
    })
    .count();
    reached == tags.len()
}

/// The grid of `seed`.
pub fn grid(seed: u64) -> TagGrid {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (cols, rows) = (rng.random_range(3..=6usize), rng.random_range(2..=4usize));
    let mut xs = vec![0.0];
    for _ in 1..cols {
        let gap = rng.random_range(0.6..1.1);
        xs.push(xs.last().copied().unwrap_or(0.0) + gap);
    }
    let mut ys = vec![0.0];
    for _ in 1..rows {
        let gap = rng.random_range(0.6..1.2);
        ys.push(ys.last().copied().unwrap_or(0.0) + gap);
    }
    let id = |c: usize, r: usize| 101 + (r * cols + c) as TagId;
    let mut tags = BTreeMap::new();
    tags.insert(DOCK, (-0.7, 0.0));
    for (r, &y) in ys.iter().enumerate() {
        for (c, &x) in xs.iter().enumerate() {
            tags.insert(id(c, r), (x, y));
        }
    }
    let mut edges = BTreeSet::new();
    edges.insert((DOCK, id(0, 0)));
    edges.insert((id(0, 0), DOCK));
    for r in 0..rows {
        for c in 0..cols {
            if c + 1 < cols {
                edges.insert((id(c, r), id(c + 1, r)));
                edges.insert((id(c + 1, r), id(c, r)));
            }
            if r + 1 < rows {
                edges.insert((id(c, r), id(c, r + 1)));
                edges.insert((id(c, r + 1), id(c, r)));
            }
        }
    }
    // Some joins left out, both ways, where the grid stays whole.
    let joins: Vec<(TagId, TagId)> = edges
        .iter()
        .copied()
        .filter(|e| e.0 < e.1 && e.0 != DOCK)
        .collect();
    for (a, b) in joins {
        if rng.random_bool(0.15) {
            let mut fewer = edges.clone();
            fewer.remove(&(a, b));
            fewer.remove(&(b, a));
            if connected(&tags, &fewer) {
                edges = fewer;
            }
        }
    }
    let grid_tags: Vec<TagId> = tags.keys().copied().filter(|&t| t != DOCK).collect();
    let tasks: Vec<Vec<TagId>> = (0..3)
        .map(|_| {
            let mut way = vec![DOCK];
            way.extend(grid_tags.choose_multiple(&mut rng, 2).copied());
            way.push(DOCK);
            way
        })
        .collect();
    let text = write_map(&tags, &edges, &tasks);
    let map = TagMap::parse(&text).expect("a generated grid is a valid tag map");
    // In every third grid a box on an edge the first task drives, where a way round it
    // is left.
    let mut obstacles = Vec::new();
    if seed.is_multiple_of(3)
        && let Ok(route) = map.route(&tasks[0], &Blocked::new())
    {
        let candidates: Vec<(TagId, TagId)> = (route.legs.iter())
            .map(|l| (l.from, l.to))
            .filter(|&(a, b)| a != DOCK && b != DOCK)
            .filter(|&(a, b)| {
                let mut fewer = edges.clone();
                fewer.remove(&(a, b));
                fewer.remove(&(b, a));
                connected(&tags, &fewer)
            })
            .collect();
        if let Some(&edge) = candidates.choose(&mut rng) {
            obstacles.push(edge);
        }
    }
    TagGrid {
        map,
        obstacles,
        text,
    }
}

fn write_map(
    tags: &BTreeMap<TagId, (f64, f64)>,
    edges: &BTreeSet<(TagId, TagId)>,
    tasks: &[Vec<TagId>],
) -> String {
    let mut text = String::from("# A generated tag grid (navdeck tags: generated).\ntags:\n");
    for (&id, &(x, y)) in tags {
        let (kind, zone) = if id == DOCK {
            ("dock", "DOCK")
        } else {
            ("waypoint", "A")
        };
        let _ = writeln!(
            text,
            "  {id}: {{x: {x:.3}, y: {y:.3}, type: {kind}, zone: {zone}}}"
        );
    }
    text.push_str("edges:\n");
    let mut from = None;
    for &(a, b) in edges {
        if from != Some(a) {
            let _ = writeln!(text, "  {a}:");
            from = Some(a);
        }
        let _ = writeln!(
            text,
            "    - {{to: {b}, direction: forward, type: straight}}"
        );
    }
    text.push_str("tasks:\n");
    for (k, way) in tasks.iter().enumerate() {
        let way: Vec<String> = way.iter().map(|t| t.to_string()).collect();
        let _ = writeln!(text, "  task{}: {{waypoints: [{}]}}", k + 1, way.join(", "));
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grids_vary_keep_every_tag_reachable_and_put_boxes_where_a_way_round_is_left() {
        let grids: Vec<TagGrid> = (1..=30).map(grid).collect();
        let sizes: BTreeSet<usize> = grids.iter().map(|g| g.map.tags.len()).collect();
        assert!(sizes.len() >= 5, "sizes {sizes:?}");
        let mut boxed = 0;
        for (k, g) in grids.iter().enumerate() {
            for name in g.map.tasks.keys() {
                let route = g.map.task_route(name, &Blocked::new()).unwrap();
                assert!(route.is_ok(), "grid {}: {name}", k + 1);
            }
            for &(a, b) in &g.obstacles {
                boxed += 1;
                let blocked: Blocked = [(a, b), (b, a)].into_iter().collect();
                let round = g.map.task_route("task1", &blocked).unwrap();
                assert!(round.is_ok(), "grid {}: no way round {a}-{b}", k + 1);
            }
        }
        assert!(boxed >= 5, "{boxed} grids with a box");
        // Some joins are missing: fewer edges than a full grid's.
        let missing = grids.iter().filter(|g| {
            let n: usize = g.map.edges.values().map(Vec::len).sum();
            let grid = g.map.tags.iter().filter(|&(&id, _)| id != DOCK);
            let distinct =
                |v: Vec<f64>| v.iter().map(|x| x.to_bits()).collect::<BTreeSet<_>>().len();
            let (c, r) = (
                distinct(grid.clone().map(|(_, t)| t.x).collect()),
                distinct(grid.map(|(_, t)| t.y).collect()),
            );
            // A full grid of c x r has 2 (2cr - c - r) directed joins, plus the dock's 2.
            n < 2 * (2 * c * r - c - r) + 2
        });
        assert!(missing.count() >= 5);
    }
}
