//! A* corner to corner across a 400 x 400 arena at 1 cm, against the `pathfinding` crate's
//! A* on the same grid, moves, integer costs and octile heuristic.

use criterion::{Criterion, criterion_group, criterion_main};
use navdeck::plan::{AStar, SearchOptions};
use std::hint::black_box;

#[path = "../tests/plan_support/mod.rs"]
mod plan_support;

fn corner_to_corner(c: &mut Criterion) {
    let map = plan_support::arena();
    let options = SearchOptions::default();
    let (start, goal) = ((2, 2), (397, 397));
    let mut astar = AStar::new();
    let ours = astar.search(&map, start, goal, &options).expect("a path");
    let (_, theirs) = plan_support::pathfinding_astar(&map, &options, start, goal).expect("a path");
    assert_eq!(
        ours.cost,
        u64::from(theirs),
        "both searches find the same cost"
    );
    eprintln!(
        "path: {} cells, cost {:.3}, {} cells expanded",
        ours.cells.len(),
        ours.cost_cells(),
        ours.expanded
    );

    let mut group = c.benchmark_group("astar_400x400");
    group.bench_function("navdeck", |b| {
        b.iter(|| {
            astar
                .search(black_box(&map), start, goal, &options)
                .map(|p| p.cost)
        })
    });
    group.bench_function("pathfinding", |b| {
        b.iter(|| {
            plan_support::pathfinding_astar(black_box(&map), &options, start, goal).map(|p| p.1)
        })
    });
    group.finish();
}

/// The costmap navdeck builds of seed 001's arena once it has seen all of it: landmark
/// rings, walls and boxes from the world; corner to corner round the three boxes.
fn surveyed_arena(c: &mut Criterion) {
    let config = navdeck::config::Config::default();
    let terrain =
        navdeck::runners::plan_report::Terrain::World(navdeck::sim::World::default_arena());
    let belief = navdeck::runners::plan_report::survey(&terrain, &config.map);
    let map = belief.costmap();
    let options = SearchOptions::default();
    let start = map
        .cell_of(navdeck::geometry::Point2::new(-1.6, -1.6))
        .unwrap();
    let goal = map
        .cell_of(navdeck::geometry::Point2::new(1.6, 1.6))
        .unwrap();
    let mut astar = AStar::new();
    let ours = astar.search(map, start, goal, &options).expect("a path");
    let (_, theirs) = plan_support::pathfinding_astar(map, &options, start, goal).expect("a path");
    assert_eq!(ours.cost, u64::from(theirs));
    eprintln!(
        "arena: {} cells, cost {:.3}, {} cells expanded",
        ours.cells.len(),
        ours.cost_cells(),
        ours.expanded
    );
    let mut group = c.benchmark_group("astar_surveyed_arena");
    group.bench_function("navdeck", |b| {
        b.iter(|| {
            astar
                .search(black_box(map), start, goal, &options)
                .map(|p| p.cost)
        })
    });
    group.bench_function("pathfinding", |b| {
        b.iter(|| {
            plan_support::pathfinding_astar(black_box(map), &options, start, goal).map(|p| p.1)
        })
    });
    group.finish();
}

criterion_group!(benches, corner_to_corner, surveyed_arena);
criterion_main!(benches);
