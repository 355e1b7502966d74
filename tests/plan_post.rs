//! Post-processing of A* paths: shortcuts stay out of obstacles and never raise the worst
//! cost, smoothing keeps the ends and the curvature of a circle, the velocity profile keeps
//! its limits, and the whole pipeline lands on the goal.

use crate::plan_support;

use navdeck::geometry::Point2;
use navdeck::map::costmap::{Costmap, LETHAL, is_lethal};
use navdeck::plan::profile::{ProfileLimits, profile};
use navdeck::plan::segment_cells::for_each_cell;
use navdeck::plan::shortcut::shortcut;
use navdeck::plan::simplify::simplify;
use navdeck::plan::smooth::{PathSample, smooth, smooth_checked};
use navdeck::plan::{AStar, PlanConfig, PlanError, Planner, SearchOptions, Smoothing};
use plan_support::{arena, random_grid};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The worst enterable cost a polyline touches, and whether it touches a lethal cell other
/// than the start cell.
fn worst_and_lethal(map: &Costmap, points: &[Point2], options: &SearchOptions) -> (u8, bool) {
    let start = map.cell_of(points[0]).unwrap();
    let (mut worst, mut lethal) = (0, false);
    for w in points.windows(2) {
        for_each_cell(map, w[0], w[1], |x, y| {
            if (x, y) != start {
                match options.traversal_cost(map.get(x, y)) {
                    Some(c) => worst = worst.max(c),
                    None => lethal = true,
                }
            }
            true
        });
    }
    (worst, lethal)
}

#[test]
fn shortcuts_avoid_obstacles_and_never_raise_the_worst_cost() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let mut astar = AStar::new();
    let options = SearchOptions::default();
    let mut shortened = 0;
    for _ in 0..1500 {
        let mut map = random_grid(&mut rng);
        // Fewer obstacles than the A* test's grids, so paths are long enough to shortcut.
        for c in map.cost.iter_mut() {
            if is_lethal(*c) && rng.random_bool(0.5) {
                *c = 0;
            }
        }
        let start = plan_support::random_cell(&mut rng, &map);
        let goal = plan_support::random_cell(&mut rng, &map);
        let Ok(path) = astar.search(&map, start, goal, &options) else {
            continue;
        };
        let keep = simplify(&path.cells);
        let centres: Vec<Point2> = path
            .cells
            .iter()
            .map(|&(x, y)| map.center_of(x, y))
            .collect();
        let (s, g) = (centres[0], *centres.last().unwrap());
        let waypoints = shortcut(&map, &path.cells, &keep, s, g, &options);
        assert_eq!(waypoints.first(), Some(&s));
        assert_eq!(waypoints.last(), Some(&g));
        // Each waypoint is a cell of the path; a segment between waypoints that are not
        // neighbours in `keep` is a shortcut, and must not cross an obstacle nor touch a cell
        // costlier than the worst cell of the stretch of path it replaces.
        let index_of = |p: Point2| {
            let c = map.cell_of(p).unwrap();
            path.cells.iter().position(|&q| q == c).unwrap()
        };
        let worst_of = |cells: &[(usize, usize)]| {
            // The start cell counts when it is enterable: starting beside a wall, the
            // robot may leave along it.
            cells
                .iter()
                .filter_map(|&(x, y)| options.traversal_cost(map.get(x, y)))
                .max()
                .unwrap_or(0)
        };
        for w in waypoints.windows(2) {
            let (ia, ib) = (index_of(w[0]), index_of(w[1]));
            assert!(ia < ib, "waypoints go backwards");
            let ka = keep.iter().position(|&k| k == ia).unwrap();
            if keep[ka + 1] == ib {
                continue; // the searched path itself
            }
            let (line_worst, lethal) = worst_and_lethal(&map, w, &options);
            assert!(!lethal, "a shortcut crosses an obstacle");
            let replaced = worst_of(&path.cells[ia..=ib]);
            assert!(line_worst <= replaced, "{line_worst} > {replaced}");
        }
        // So the worst cell the robot is sent through never gets worse.
        if waypoints.len() < keep.len() {
            shortened += 1;
        }
    }
    assert!(shortened > 200, "only {shortened} paths were shortened");
}

#[test]
fn smoothing_starts_at_the_start_and_ends_at_the_goal() {
    let corner = [
        Point2::new(0.0, 0.0),
        Point2::new(1.0, 0.0),
        Point2::new(1.0, 0.7),
    ];
    let samples = smooth(&corner, 0.1, 0.01);
    assert_eq!(samples[0].position, corner[0]);
    assert_eq!(samples.last().unwrap().position, corner[2]);
    // About one sample per centimetre of the 1.7 m polyline.
    assert!((165..=175).contains(&samples.len()), "{}", samples.len());
    // Straight stretches stay straight: a sample 0.5 m along lies on the first segment.
    let mid = samples.iter().find(|s| s.position.x >= 0.5).unwrap();
    assert!(mid.position.y.abs() < 1e-9 && mid.curvature.abs() < 1e-6);
    // The corner is rounded: a left turn, tighter than a metre's radius.
    let max = samples.iter().map(|s| s.curvature).fold(f64::MIN, f64::max);
    assert!(max > 1.0);
    // One point and two points, per seed 004.
    let one = smooth(&corner[..1], 0.1, 0.01);
    assert_eq!(one.len(), 1);
    assert_eq!(one[0].curvature, 0.0);
    let two = smooth(&corner[..2], 0.1, 0.01);
    assert_eq!(two.len(), 101);
    assert!(
        two.iter()
            .all(|s| s.curvature == 0.0 && s.position.y == 0.0)
    );
}

#[test]
fn smoothing_a_finely_sampled_circle_gives_its_curvature() {
    // Half a circle of radius 0.5 m, counter-clockwise: curvature +2 /m.
    let r = 0.5;
    let arc: Vec<Point2> = (0..=200)
        .map(|i| {
            let a = std::f64::consts::PI * i as f64 / 200.0;
            Point2::new(r * a.cos(), r * a.sin())
        })
        .collect();
    let samples = smooth(&arc, 0.1, 0.01);
    let n = samples.len();
    for s in &samples[n / 10..n - n / 10] {
        assert!(
            (s.curvature - 1.0 / r).abs() < 0.01,
            "curvature {}",
            s.curvature
        );
        let radius = s.position.x.hypot(s.position.y);
        assert!((radius - r).abs() < 1e-3);
    }
}

#[test]
fn smoothing_falls_back_when_the_curve_would_clip_an_obstacle() {
    let mut map = Costmap::new(100, 100, 0.01, Point2::new(0.0, 0.0), 0);
    // An obstacle filling the inside of a corner right up to the polyline.
    for x in 0..49 {
        for y in 51..100 {
            map.set(x, y, LETHAL);
        }
    }
    let corner = [
        Point2::new(0.05, 0.505),
        Point2::new(0.495, 0.505),
        Point2::new(0.495, 0.95),
    ];
    let options = SearchOptions::default();
    let (samples, how) = smooth_checked(&corner, &map, &options, 0.1, 0.01);
    for s in &samples {
        assert!(
            !is_lethal(map.at(s.position)),
            "sample {:?} in the obstacle",
            s.position
        );
    }
    assert_ne!(
        how,
        Smoothing::Spline {
            control_spacing: 0.1
        }
    );
    assert_eq!(samples.last().unwrap().position, corner[2]);
}

fn check_profile(samples: &[PathSample], limits: &ProfileLimits) {
    let traj = profile(samples, limits);
    let p = &traj.points;
    assert_eq!(p.len(), samples.len());
    assert_eq!(p[0].v, 0.0);
    assert_eq!(p.last().unwrap().v, 0.0);
    for q in p {
        assert!(q.v <= limits.max_speed + 1e-12);
        if q.curvature != 0.0 {
            assert!(q.v <= (limits.max_lateral_accel / q.curvature.abs()).sqrt() + 1e-12);
        }
    }
    for w in p.windows(2) {
        let ds = w[1].s - w[0].s;
        let dv2 = (w[1].v * w[1].v - w[0].v * w[0].v).abs();
        assert!(dv2 <= 2.0 * limits.max_accel * ds + 1e-12, "{w:?}");
        assert!(w[1].t > w[0].t, "time stands still: {w:?}");
    }
}

#[test]
fn the_velocity_profile_keeps_speed_turn_and_acceleration_limits() {
    let limits = ProfileLimits::default();
    // A long straight: reaches top speed, accelerating and braking at the limit.
    let straight = smooth(&[Point2::new(0.0, 0.0), Point2::new(2.0, 0.0)], 0.1, 0.01);
    check_profile(&straight, &limits);
    let traj = profile(&straight, &limits);
    let top = traj.points.iter().map(|p| p.v).fold(0.0, f64::max);
    assert_eq!(top, limits.max_speed);
    // 0.22 m/s reached after v^2 / 2a = 0.04 m; the trip takes 2 / 0.22 + 0.22 / 0.6 s.
    assert!(
        (traj.duration() - (2.0 / 0.22 + 0.22 / 0.6)).abs() < 0.01,
        "{}",
        traj.duration()
    );
    // A zig-zag with tight corners slows for each turn.
    let zigzag = smooth(
        &[
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 0.0),
            Point2::new(1.0, 1.0),
            Point2::new(2.0, 0.0),
        ],
        0.05,
        0.01,
    );
    check_profile(&zigzag, &limits);
    let traj = profile(&zigzag, &limits);
    let at_corner = traj
        .points
        .iter()
        .max_by(|a, b| a.curvature.abs().total_cmp(&b.curvature.abs()))
        .unwrap();
    assert!(at_corner.v < 0.5 * limits.max_speed, "{at_corner:?}");
    // One point: one sample at t = 0.
    let one = profile(&straight[..1], &limits);
    assert_eq!(one.points.len(), 1);
    assert_eq!((one.points[0].t, one.points[0].v), (0.0, 0.0));
}

#[test]
fn the_planner_reaches_the_goal_across_the_arena() {
    let map = arena();
    let (start, goal) = (Point2::new(0.023, 0.021), Point2::new(3.971, 3.968));
    let mut planner = Planner::new();
    let config = PlanConfig::default();
    let plan = planner.plan(&map, start, goal, &config).unwrap();
    assert_eq!(plan.waypoints.first(), Some(&start));
    assert_eq!(plan.waypoints.last(), Some(&goal));
    assert!(
        plan.waypoints.len() < 20,
        "{} waypoints",
        plan.waypoints.len()
    );
    let traj = &plan.trajectory;
    assert_eq!(traj.points[0].position, start);
    assert_eq!(traj.goal(), Some(goal));
    assert!(traj.points.iter().all(|p| !is_lethal(map.at(p.position))));
    assert!(traj.points.iter().all(|p| p.v <= config.max_speed + 1e-12));
    assert_eq!(plan.length, traj.length());
    assert!(
        matches!(plan.smoothing, Smoothing::Spline { .. }),
        "{:?}",
        plan.smoothing
    );
    // The detours around the walls make it much longer than the 5.6 m diagonal.
    assert!(plan.length > 8.0 && plan.length < 12.0, "{}", plan.length);
    assert!(plan.cost > 976.0 && plan.expanded > 1000);

    // Each switch off: the raw cells, still ending exactly at the goal.
    let raw = PlanConfig {
        simplify: false,
        shortcut: false,
        smooth: false,
        ..PlanConfig::default()
    };
    let plain = planner.plan(&map, start, goal, &raw).unwrap();
    assert_eq!(plain.waypoints.len(), plain.cells.len());
    assert_eq!(plain.smoothing, Smoothing::Off);
    assert_eq!(plain.cost, plan.cost);
}

#[test]
fn the_planner_names_bad_goals_and_bad_settings() {
    let map = arena();
    let mut planner = Planner::new();
    let config = PlanConfig::default();
    let start = Point2::new(0.05, 0.05);
    let inside = Point2::new(1.025, 1.5);
    match planner.plan(&map, start, inside, &config) {
        Err(PlanError::GoalInObstacle { x, y, cost }) => {
            assert_eq!((x, y, cost), (inside.x, inside.y, LETHAL));
        }
        other => panic!("{other:?}"),
    }
    let off = Point2::new(5.0, 1.0);
    let err = planner.plan(&map, start, off, &config).unwrap_err();
    assert_eq!(err.to_string(), "goal (5.000, 1.000) is off the map");
    let bad = PlanConfig {
        max_speed: 0.0,
        ..PlanConfig::default()
    };
    let err = planner
        .plan(&map, start, Point2::new(0.5, 0.5), &bad)
        .unwrap_err();
    assert!(err.to_string().starts_with("plan.max_speed = 0"), "{err}");
}
