//! A* against a plain Dijkstra and the `pathfinding` crate: same costs, legal paths, and the
//! errors a user sees when the goal is in an obstacle or cut off.

use crate::plan_support;

use navdeck::geometry::Point2;
use navdeck::map::costmap::Costmap;
use navdeck::map::costmap::{LETHAL, NO_INFORMATION, is_lethal};
use navdeck::plan::astar::{CARDINAL, DIAGONAL, PENALTY_PER_COST};
use navdeck::plan::{AStar, PlanError, SearchOptions};
use plan_support::{arena, moves, pathfinding_astar, penalty, random_grid};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// A plain Dijkstra over the same moves: the cheapest cost, or None if the goal is blocked
/// or unreachable.
fn dijkstra(
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

/// Recomputes a path's cost from its steps, checking each step is a legal move.
fn walk_cost(map: &Costmap, options: &SearchOptions, cells: &[(usize, usize)]) -> u64 {
    let mut total = 0u64;
    for w in cells.windows(2) {
        let (a, b) = (w[0], w[1]);
        let (dx, dy) = (a.0.abs_diff(b.0), a.1.abs_diff(b.1));
        assert!(
            dx <= 1 && dy <= 1 && dx + dy > 0,
            "{a:?} -> {b:?} is not one step"
        );
        let raw = map.get(b.0, b.1);
        assert!(
            !is_lethal(raw),
            "the path enters lethal cell {b:?} (cost {raw})"
        );
        let cost = options.traversal_cost(raw).expect("an enterable cell");
        if dx + dy == 2 {
            let side_a = options.traversal_cost(map.get(b.0, a.1));
            let side_b = options.traversal_cost(map.get(a.0, b.1));
            assert!(
                side_a.is_some() || side_b.is_some(),
                "{a:?} -> {b:?} cuts a corner"
            );
        }
        let step = if dx + dy == 2 { DIAGONAL } else { CARDINAL };
        total += u64::from(step + PENALTY_PER_COST * u32::from(cost));
    }
    total
}

#[test]
fn astar_costs_match_dijkstra_on_random_grids() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut astar = AStar::new();
    let (mut found, mut unreachable, mut in_obstacle) = (0, 0, 0);
    for round in 0..1500 {
        let map = random_grid(&mut rng);
        let options = SearchOptions {
            allow_unknown: rng.random_bool(0.5),
            unknown_cost: rng.random_range(0..100),
        };
        let start = plan_support::random_cell(&mut rng, &map);
        let goal = plan_support::random_cell(&mut rng, &map);
        let reference = dijkstra(&map, &options, start, goal);
        match astar.search(&map, start, goal, &options) {
            Ok(path) => {
                found += 1;
                assert_eq!(Some(path.cost), reference, "round {round}");
                assert_eq!(path.cells.first(), Some(&start));
                assert_eq!(path.cells.last(), Some(&goal));
                assert_eq!(walk_cost(&map, &options, &path.cells), path.cost);
            }
            Err(e) => {
                assert_eq!(reference, None, "round {round}: A* failed with {e}");
                match e {
                    PlanError::Unreachable { .. } => unreachable += 1,
                    PlanError::GoalInObstacle { cost, .. } => {
                        assert!(is_lethal(cost));
                        in_obstacle += 1
                    }
                    PlanError::GoalUnknown { .. } => {
                        assert!(!options.allow_unknown);
                        assert_eq!(map.get(goal.0, goal.1), NO_INFORMATION);
                    }
                    other => panic!("unexpected error {other}"),
                }
            }
        }
    }
    // The random grids exercise every outcome.
    assert!(
        found > 500 && unreachable > 50 && in_obstacle > 100,
        "{found} {unreachable} {in_obstacle}"
    );
}

#[test]
fn astar_matches_the_pathfinding_crate_on_the_benchmark_arena() {
    let map = arena();
    let options = SearchOptions::default();
    let (start, goal) = ((2, 2), (397, 397));
    let ours = AStar::new().search(&map, start, goal, &options).unwrap();
    let (_, theirs) = pathfinding_astar(&map, &options, start, goal).unwrap();
    assert_eq!(ours.cost, u64::from(theirs));
    assert_eq!(walk_cost(&map, &options, &ours.cells), ours.cost);
}

#[test]
fn a_goal_inside_an_obstacle_is_refused_naming_its_cost() {
    let mut map = Costmap::new(10, 10, 0.1, Point2::new(0.0, 0.0), 0);
    map.set(7, 7, LETHAL);
    let err = AStar::new()
        .search(&map, (1, 1), (7, 7), &SearchOptions::default())
        .unwrap_err();
    assert!(matches!(
        err,
        PlanError::GoalInObstacle { cost: LETHAL, .. }
    ));
    assert!(
        err.to_string()
            .contains("inside an obstacle (cell cost 100)"),
        "{err}"
    );
}

#[test]
fn a_walled_off_goal_is_unreachable_after_searching_the_start_side() {
    let mut map = Costmap::new(10, 10, 0.1, Point2::new(0.0, 0.0), 0);
    for y in 0..10 {
        map.set(5, y, LETHAL);
    }
    let err = AStar::new()
        .search(&map, (1, 1), (8, 8), &SearchOptions::default())
        .unwrap_err();
    // Every cell left of the wall is searched, none beyond it.
    assert!(
        matches!(err, PlanError::Unreachable { expanded: 50, .. }),
        "{err}"
    );
}

#[test]
fn a_diagonal_gap_between_two_obstacles_is_not_squeezed_through() {
    let mut map = Costmap::new(4, 4, 0.1, Point2::new(0.0, 0.0), LETHAL);
    // Free cells (1, 1) and (2, 2) touch only at a corner between lethal (2, 1) and (1, 2).
    map.set(1, 1, 0);
    map.set(2, 2, 0);
    let result = AStar::new().search(&map, (1, 1), (2, 2), &SearchOptions::default());
    assert!(matches!(result, Err(PlanError::Unreachable { .. })));
    map.set(2, 1, 0);
    let path = AStar::new()
        .search(&map, (1, 1), (2, 2), &SearchOptions::default())
        .unwrap();
    assert_eq!(path.cells, vec![(1, 1), (2, 2)]);
}

#[test]
fn a_robot_standing_in_an_obstacle_can_still_leave_it() {
    let mut map = Costmap::new(6, 6, 0.1, Point2::new(0.0, 0.0), 0);
    map.set(0, 0, LETHAL);
    map.set(1, 0, LETHAL);
    let path = AStar::new()
        .search(&map, (0, 0), (4, 4), &SearchOptions::default())
        .unwrap();
    assert_eq!(path.cost_cells(), 4.0 * 1.414);
}

#[test]
fn unknown_space_is_avoided_or_crossed_as_configured() {
    let mut map = Costmap::new(9, 3, 0.1, Point2::new(0.0, 0.0), 0);
    for y in 0..3 {
        map.set(4, y, NO_INFORMATION);
    }
    let mut astar = AStar::new();
    let closed = SearchOptions {
        allow_unknown: false,
        unknown_cost: 0,
    };
    assert!(astar.search(&map, (0, 1), (8, 1), &closed).is_err());
    let costly = SearchOptions {
        allow_unknown: true,
        unknown_cost: 40,
    };
    let path = astar.search(&map, (0, 1), (8, 1), &costly).unwrap();
    assert_eq!(path.cost, 8 * 1000 + 40 * 50);
}
