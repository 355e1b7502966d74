//! Goals, waypoints and the command line as a Nav2 or RViz user meets them: a failed goal
//! keeps the one being followed; a route of waypoints driven in order, looped, saved and
//! loaded; `:` history and Tab completion; the pose arrow, the cursor over the truth
//! marker, panning and fast moves in thinking mode.

use crate::common;

use common::{default_app, key, logged, render_at, scratch};
use navdeck::app::mode::Mode;
use navdeck::app::{App, KeyKind};
use navdeck::geometry::Point2;
use navdeck::keymap::parse_key_sequence;
use navdeck::runners::headless;
use navdeck::session::{Session, SessionSpec};
use navdeck::sim::generate::{GenerateOptions, Style, generate};

/// Plays `keys` headless and returns the report.
fn play(app: &mut App, keys: &str) -> headless::Report {
    headless::run(app, &parse_key_sequence(keys).unwrap(), 10.0)
}

/// Types `line` after `:` without pressing enter.
fn type_line(app: &mut App, line: &str) {
    let t = app.now();
    app.handle_key(key(":"), KeyKind::Press, t);
    for c in line.chars() {
        let name = if c == ' ' {
            "space".to_string()
        } else {
            c.to_string()
        };
        app.handle_key(key(&name), KeyKind::Press, t);
    }
}

fn press(app: &mut App, name: &str) {
    let t = app.now();
    app.handle_key(key(name), KeyKind::Press, t);
}

#[test]
fn a_failed_goto_while_following_keeps_the_goal_and_the_robot_arrives() {
    let mut app = default_app();
    // Marker 311 faces the robot's start; marker 999 is on no map.
    let report = play(&mut app, ":goto marker 311<enter>p:goto marker 999<enter>");
    assert!(logged(&app, "no path to marker 999"));
    assert!(
        logged(
            &app,
            "goal marker 999 refused; still following the path to marker 311"
        ),
        "the log says the new goal was refused and the old one kept"
    );
    assert!(report.following.arrived, "warnings: {:?}", report.warnings);
    assert_eq!(app.pilot().route().unwrap().label, "marker 311");
    let marker = app.pilot().slam().landmark(311).unwrap().mean;
    let p = report.travel.true_pose.unwrap();
    assert!(
        (p.x - marker.x).hypot(p.y - marker.y) < 0.3,
        "ended at {p:?}"
    );
}

#[test]
fn a_goal_that_cannot_be_planned_keeps_the_path_planned_before() {
    let mut app = default_app();
    // Thinking mode: a path to (0.9, 0.6), then a goal far off the map.
    play(&mut app, ":goto 0.9 0.6<enter>:goto 80 80<enter>");
    assert!(logged(
        &app,
        "goal (80.00, 80.00) refused; the path to (0.90, 0.60) is kept"
    ));
    assert_eq!(app.pilot().route().unwrap().label, "(0.90, 0.60)");
    let report = play(&mut app, "p");
    assert!(report.following.arrived, "warnings: {:?}", report.warnings);
}

/// A generated world's console, and five goals in its free space, each 1 to 2 m from the
/// one before, well clear of walls, boxes and blocks.
fn generated_route() -> (App, Vec<Point2>) {
    let options = GenerateOptions {
        seed: 7,
        style: Style::Boxes,
        ..GenerateOptions::default()
    };
    let world = generate(&options).expect("the world generates");
    let blocks: Vec<Point2> = world.blocks.iter().map(|b| b.pose.position()).collect();
    let start = world.start.position();
    let app = Session::load_with_world(&SessionSpec::twin(None), world)
        .expect("session loads")
        .into_app(0.0);
    let grid = app.world_grid().expect("the twin's walls").clone();
    let (_, (w, h)) = app.world_extent();
    let clear = |p: Point2, r: f64| {
        common::clear_round(&grid, (w, h), p, r) && blocks.iter().all(|b| b.distance(p) > 0.5)
    };
    let line_clear = |a: Point2, b: Point2| {
        let n = (a.distance(b) / 0.05).ceil() as usize;
        (0..=n).all(|k| {
            let t = k as f64 / n as f64;
            clear(
                Point2::new(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)),
                0.3,
            )
        })
    };
    let mut candidates = Vec::new();
    let mut y = -h / 2.0;
    while y < h / 2.0 {
        let mut x = -w / 2.0;
        while x < w / 2.0 {
            let p = Point2::new(x, y);
            if clear(p, 0.4) {
                candidates.push(p);
            }
            x += 0.25;
        }
        y += 0.25;
    }
    let mut goals: Vec<Point2> = Vec::new();
    let mut from = start;
    while goals.len() < 5 {
        let next = candidates
            .iter()
            .copied()
            .filter(|p| (1.0..2.0).contains(&p.distance(from)))
            .filter(|p| goals.iter().all(|g| g.distance(*p) > 0.8))
            .filter(|p| line_clear(from, *p))
            .min_by(|a, b| {
                a.distance(from)
                    .total_cmp(&b.distance(from))
                    .then(a.x.total_cmp(&b.x))
            })
            .expect("a next goal");
        goals.push(next);
        from = next;
    }
    (app, goals)
}

/// How far the filter's estimate may be from the twin at an arrival, metres (the EKF's
/// bar in tests/slam_ekf.rs is ±5 cm).
const ESTIMATE_ERROR: f64 = 0.05;

#[test]
fn a_route_of_five_goals_is_driven_in_order_twice_and_reads_back_from_its_file() {
    let (mut app, goals) = generated_route();
    let file = scratch("route").join("five.yaml");
    let mut keys = String::new();
    for g in &goals {
        keys.push_str(&format!(":waypoint add {:.2} {:.2}<enter>", g.x, g.y));
    }
    let path = file.display();
    keys.push_str(&format!(":route loop 2<enter>:route save {path}<enter>"));
    play(&mut app, &keys);
    let queued = app.pilot().waypoints().goals().to_vec();
    assert_eq!(queued.len(), 5);
    let text = std::fs::read_to_string(&file).expect("the route file is written");
    assert!(
        text.contains("frame_id: map") && text.contains("loops: 2"),
        "{text}"
    );
    // Cleared, then loaded back: the same route.
    play(
        &mut app,
        &format!(":route clear<enter>:route load {path}<enter>"),
    );
    assert_eq!(app.pilot().waypoints().goals(), queued.as_slice());
    assert_eq!(app.pilot().waypoints().loops(), 2);

    let report = play(&mut app, ":route start<enter>");
    assert!(
        logged(&app, "route done: 5 waypoints, 2 loop(s)"),
        "warnings: {:?}",
        report.warnings
    );
    assert_eq!(report.collisions, Some(0));
    let arrivals = app.pilot().waypoints().arrivals();
    let order: Vec<(usize, usize)> = arrivals.iter().map(|a| (a.lap, a.index)).collect();
    let expected: Vec<(usize, usize)> = (0..2)
        .flat_map(|lap| (0..5).map(move |i| (lap, i)))
        .collect();
    assert_eq!(order, expected, "every waypoint once per loop, in order");
    let tolerance = app.config().follow.goal_tolerance;
    for a in arrivals {
        let truth = a.truth.expect("the twin's truth").position();
        let goal = queued[a.index].position;
        // The pilot judges arrival by its estimate, as Nav2's goal checker does; the
        // twin is truly there within that tolerance plus the estimate's own error.
        let estimate = a.estimate.position();
        let (lap, index) = (a.lap + 1, a.index + 1);
        assert!(
            estimate.distance(goal) <= tolerance,
            "waypoint {index} loop {lap}: the estimate is {:.3} m from it",
            estimate.distance(goal)
        );
        assert!(
            truth.distance(estimate) <= ESTIMATE_ERROR,
            "waypoint {index} loop {lap}: the estimate is {:.3} m off the twin",
            truth.distance(estimate)
        );
        assert!(
            truth.distance(goal) <= tolerance + truth.distance(estimate) + 1e-9,
            "waypoint {index} loop {lap}: the twin is {:.3} m from it",
            truth.distance(goal)
        );
        assert!(a.time > 0.0);
    }
    assert!(arrivals.windows(2).all(|w| w[0].time < w[1].time));
}

#[test]
fn route_progress_pause_skip_and_a_goal_of_its_own() {
    let mut app = default_app();
    play(
        &mut app,
        ":waypoint add 0.9 0.6<enter>:goto+ 0.9 -0.6<enter>:goto+ -0.6 -0.6 90<enter>:route loop 2<enter>",
    );
    assert!(render_at(&app, 120, 40).contains("3 waypoints x2 loops"));
    let t = app.now();
    app.handle_key(key(":"), KeyKind::Press, t);
    for k in parse_key_sequence("route start<enter>").unwrap() {
        app.handle_key(k, KeyKind::Press, t);
    }
    assert_eq!(app.pilot().mode(), Mode::PathFollowing);
    assert!(render_at(&app, 120, 40).contains("waypoint 1/3, loop 1/2"));
    play_now(&mut app, ":route skip<enter>");
    assert_eq!(app.pilot().waypoints().current(), Some(1));
    play_now(&mut app, ":route pause<enter>");
    assert_eq!(app.pilot().mode(), Mode::Manual);
    assert!(logged(&app, "route paused before waypoint 2"));
    // A goal of its own replaces the route, as in Nav2.
    play_now(&mut app, ":goto 0.5 0.0<enter>");
    assert!(!app.pilot().waypoints().is_active());
    assert!(logged(&app, "route stopped: the new goal replaces it"));
    play_now(&mut app, ":route clear<enter>");
    assert!(app.pilot().waypoints().goals().is_empty());
}

/// Presses `keys` at the app's present time, nothing run in between.
fn play_now(app: &mut App, keys: &str) {
    let t = app.now();
    for k in parse_key_sequence(keys).unwrap() {
        app.handle_key(k, KeyKind::Press, t);
    }
}

#[test]
fn a_bad_route_file_is_named_with_its_field_and_value() {
    let dir = scratch("bad-route");
    let file = dir.join("bad.yaml");
    std::fs::write(
        &file,
        "frame_id: map\nwaypoints:\n  - {x: 1.0, y: 2.0}\n  - {x: 1.0, y: .inf}\n",
    )
    .unwrap();
    let mut app = default_app();
    play_now(&mut app, &format!(":route load {}<enter>", file.display()));
    let line = app
        .log_book()
        .iter()
        .find(|e| e.text.starts_with("route not loaded"))
        .expect("the load is refused")
        .text
        .clone();
    assert!(
        line.contains("bad.yaml") && line.contains("waypoints[1].y") && line.contains("inf"),
        "{line}"
    );
    assert!(app.pilot().waypoints().goals().is_empty());
}

#[test]
fn up_and_down_recall_earlier_commands_as_a_shell_does() {
    let mut app = default_app();
    play_now(&mut app, ":controller pid<enter>:goto 0.9 0.6<enter>");
    type_line(&mut app, "go");
    press(&mut app, "up");
    assert_eq!(app.prompt(), Some("goto 0.9 0.6"));
    press(&mut app, "up");
    assert_eq!(app.prompt(), Some("controller pid"));
    press(&mut app, "up");
    assert_eq!(app.prompt(), Some("controller pid"), "the oldest stays");
    press(&mut app, "down");
    assert_eq!(app.prompt(), Some("goto 0.9 0.6"));
    press(&mut app, "down");
    assert_eq!(
        app.prompt(),
        Some("go"),
        "down past the newest: the line being typed"
    );
    press(&mut app, "esc");
    assert_eq!(app.prompt(), None);
}

#[test]
fn tab_completes_commands_marker_ids_and_map_names() {
    let mut app = default_app();
    type_line(&mut app, "rel");
    press(&mut app, "tab");
    assert_eq!(app.prompt(), Some("relocalize "));
    press(&mut app, "esc");
    type_line(&mut app, "ro");
    press(&mut app, "tab");
    assert_eq!(app.prompt(), Some("route "));
    press(&mut app, "esc");
    // Marker 311 is seen from the start: its ID completes.
    play(&mut app, "");
    assert!(app.pilot().slam().landmark(311).is_some());
    type_line(&mut app, "goto marker 31");
    press(&mut app, "tab");
    let line = app.prompt().unwrap().to_string();
    assert!(line.starts_with("goto marker 31"), "{line}");
    press(&mut app, "esc");
    // Map names from the maps folder; routes are not maps.
    let dir = scratch("tab-maps");
    for f in [
        "turtlebot3_world.yaml",
        "arena_saved.yaml",
        "five.route.yaml",
    ] {
        std::fs::write(dir.join(f), "").unwrap();
    }
    app.set_maps_dir(dir);
    type_line(&mut app, "save tu");
    press(&mut app, "tab");
    assert_eq!(app.prompt(), Some("save turtlebot3_world "));
    press(&mut app, "esc");
    type_line(&mut app, "route load f");
    press(&mut app, "tab");
    assert_eq!(app.prompt(), Some("route load five "));
    press(&mut app, "esc");
    // Several left: completed as far as they agree, and listed in the log.
    type_line(&mut app, "go");
    press(&mut app, "tab");
    assert_eq!(app.prompt(), Some("goto"));
    assert!(logged(&app, "Tab: goto  goto+"));
}

#[test]
fn capital_hjkl_move_the_cursor_ten_cells_and_the_map_pans_to_keep_it() {
    let mut app = default_app();
    app.resize(80, 24);
    play_now(&mut app, "tl");
    let one = app.goal_cursor().unwrap();
    play_now(&mut app, "L");
    let ten = app.goal_cursor().unwrap();
    let cell = app.view().scale(app.fitted_scale());
    assert!(
        ((ten.x - one.x) - 10.0 * cell).abs() < 1e-9,
        "{one:?} {ten:?}"
    );
    // Far past the map's edge: the view follows the cursor.
    play_now(&mut app, "LLLLLLLLLL");
    let c = app.goal_cursor().unwrap();
    let (centre, (w, _)) = (app.map_center(), app.map_span());
    assert!(
        (c.x - centre.x).abs() < w / 2.0,
        "cursor {c:?} off the map at {centre:?}"
    );
}

#[test]
fn ctrl_arrows_pan_the_map_while_the_arrows_move_the_cursor() {
    let mut app = default_app();
    play_now(&mut app, "t+<right>");
    let (before, cursor) = (app.map_center(), app.goal_cursor().unwrap());
    play_now(&mut app, "<ctrl-right><ctrl-up>");
    let after = app.map_center();
    assert!(
        after.x > before.x && after.y > before.y,
        "{before:?} -> {after:?}"
    );
    assert_eq!(app.goal_cursor(), Some(cursor), "panning leaves the cursor");
    assert_eq!(app.pilot().mode(), Mode::Thinking);
}

#[test]
fn the_goal_cursor_is_drawn_over_the_truth_marker() {
    let mut app = default_app();
    play(&mut app, "");
    assert!(app.view().show_truth, "the twin's true pose `o` is drawn");
    let marks = |app: &App| render_at(app, 120, 40).matches('X').count();
    // The cursor one cell off the robot, then back on it, where `o` and `@` are drawn.
    play_now(&mut app, "tl");
    let beside = marks(&app);
    play_now(&mut app, "h");
    assert_eq!(marks(&app), beside, "the cursor stays visible on the robot");
}

fn arrow_app() -> App {
    let mut app = default_app();
    play(&mut app, "");
    // Anchor at the robot, then the cursor up and to the right: an arrow between them.
    play_now(&mut app, "tPllllllllkkk");
    app
}

#[test]
fn pose_arrow_80x24() {
    let app = arrow_app();
    let screen = render_at(&app, 80, 24);
    assert!(screen.contains('↗') || screen.contains('→'), "{screen}");
    insta::assert_snapshot!(screen);
}

#[test]
fn pose_arrow_120x40() {
    insta::assert_snapshot!(render_at(&arrow_app(), 120, 40));
}

#[test]
fn pose_arrow_240x60() {
    insta::assert_snapshot!(render_at(&arrow_app(), 240, 60));
}

fn numbered_app() -> App {
    let mut app = default_app();
    play(
        &mut app,
        ":waypoint add 0.9 0.6<enter>:goto+ 0.9 -0.6<enter>:goto+ -0.6 -0.6 90<enter>:route loop 2<enter>",
    );
    app
}

#[test]
fn numbered_waypoints_80x24() {
    let screen = render_at(&numbered_app(), 80, 24);
    insta::assert_snapshot!(screen);
}

#[test]
fn numbered_waypoints_240x60() {
    let screen = render_at(&numbered_app(), 240, 60);
    assert!(screen.contains("3 waypoints x2 loops"), "{screen}");
    insta::assert_snapshot!(screen);
}

#[test]
fn numbered_waypoints_120x40() {
    let screen = render_at(&numbered_app(), 120, 40);
    for n in ['1', '2', '3'] {
        assert!(screen.contains(n));
    }
    insta::assert_snapshot!(screen);
}
