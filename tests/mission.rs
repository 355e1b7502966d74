//! The mission end to end: exploration mode in the console and `navdeck mission`.

use crate::common;

use common::{default_app, generated_mission, key, logged, navdeck};
use navdeck::app::KeyKind;
use navdeck::app::mode::Mode;
use navdeck::runners::mission as mission_runner;
use navdeck::sim::World;
use serde_json::Value;
use std::path::Path;

#[test]
fn the_mission_delivers_all_four_blocks_without_touching_anything() {
    let out = navdeck(&["mission", "--seed", "2", "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    let r: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(r["delivered"], 4);
    assert_eq!(
        r["true_delivered"], 4,
        "the twin has every block at its gate"
    );
    assert_eq!(r["collisions"], 0);
    // The block being picked, in the jaws' mouth, never stops the creep up to it: its
    // near face, too near for the lidar by then, is the block and not an obstacle.
    let warnings = r["warnings"].as_array().unwrap();
    let held_up = warnings.iter().filter_map(Value::as_str);
    let held_up: Vec<&str> = held_up
        .filter(|w| w.contains("(was pick and place): stopping"))
        .collect();
    assert!(held_up.is_empty(), "{held_up:?}");
    let timeline = r["timeline"].as_array().unwrap();
    assert_eq!(timeline.len(), 4);
    for block in timeline {
        let (found, picked, delivered) = (
            block["found"].as_f64().unwrap(),
            block["picked"].as_f64().unwrap(),
            block["delivered"].as_f64().unwrap(),
        );
        assert!(found <= picked && picked < delivered, "{block}");
    }
    for field in [
        "replans",
        "recoveries",
        "position_rmse",
        "position_max_error",
        "heading_rmse_deg",
        "map_vs_walls",
        "wall_time_s",
    ] {
        assert!(!r[field].is_null(), "{field}");
    }
}

#[test]
fn a_mission_on_a_generated_world_scores_its_map_against_the_true_walls() {
    let out = navdeck(&[
        "mission",
        "--generated",
        "--style",
        "rooms",
        "--seed",
        "3",
        "--time-limit",
        "60",
        "--json",
    ]);
    let r: Value = serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(&out.stderr)));
    let map = &r["map_vs_walls"];
    let share = |field: &str| {
        map[field]
            .as_f64()
            .unwrap_or_else(|| panic!("{field}: {r}"))
    };
    let (recall, precision) = (share("wall_recall"), share("wall_precision"));
    // A minute of exploring has mapped some of the walls, and mostly walls.
    assert!(recall > 0.0 && recall <= 1.0, "{map}");
    assert!(precision > 0.0 && precision <= 1.0, "{map}");
    assert!(map["wall_cells"].as_u64().unwrap() > 0, "{map}");
    let rmse = r["position_rmse"].as_f64().unwrap();
    let max = r["position_max_error"].as_f64().unwrap();
    assert!(max >= rmse && max > 0.0, "max {max} < RMSE {rmse}");
    // The person's report says it too.
    let out = navdeck(&[
        "mission",
        "--generated",
        "--style",
        "rooms",
        "--seed",
        "3",
        "--time-limit",
        "60",
    ]);
    let said = String::from_utf8_lossy(&out.stdout);
    assert!(
        said.contains("walls mapped") && said.contains(", max "),
        "{said}"
    );
}

#[test]
fn a_sweep_sums_up_the_seeds_and_a_time_limit_fails_the_run() {
    let out = navdeck(&["mission", "--sweep", "3..4", "--json"]);
    let s: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(s["runs"], 2);
    assert!(s["median_sim_time"].as_f64().unwrap() > 0.0);
    assert_eq!(s["success_rate"], 1.0, "{s}");
    for figure in [
        "position_rmse",
        "position_max_error",
        "wall_recall",
        "wall_precision",
    ] {
        let spread = &s[figure];
        let (min, mean, max) = (
            spread["min"].as_f64(),
            spread["mean"].as_f64(),
            spread["max"].as_f64(),
        );
        let (min, mean, max) = (min.unwrap(), mean.unwrap(), max.unwrap());
        assert!(min <= mean && mean <= max, "{figure}: {spread}");
    }
    let short = navdeck(&["mission", "--seed", "1", "--time-limit", "30", "--json"]);
    assert_eq!(short.status.code(), Some(1), "a mission cut short fails");
    let r: Value = serde_json::from_slice(&short.stdout).unwrap();
    assert_eq!(r["outcome"], "time limit");
    let bad = navdeck(&["mission", "--sweep", "9..3"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("`9..3`"));
}

#[test]
fn seed_ranges_parse() {
    assert_eq!(mission_runner::parse_seeds("1..3"), Ok(vec![1, 2, 3]));
    assert_eq!(mission_runner::parse_seeds("7"), Ok(vec![7]));
    assert!(mission_runner::parse_seeds("a..b").is_err());
}

#[test]
fn in_the_console_e_starts_the_mission_and_a_drive_key_takes_over() {
    let mut app = default_app();
    app.handle_key(key("e"), KeyKind::Press, 0.0);
    assert_eq!(app.pilot().mode(), Mode::Exploration);
    for k in 1..=300 {
        app.update(0.1 * f64::from(k));
    }
    let mission = app.pilot().mission().expect("a mission runs");
    assert!(mission.known_blocks() >= 1, "{}", mission.state_label());
    assert!(
        app.log_book().iter().any(|e| e.text.starts_with("Found ")),
        "seed-style log lines"
    );
    let moving = app.pilot().commanded();
    assert!(!moving.is_zero() || app.true_pose().is_some());
    app.handle_key(key("w"), KeyKind::Press, 30.05);
    assert_eq!(app.pilot().mode(), Mode::Manual);
    assert!(app.pilot().commanded().linear > 0.0, "w drives at once");
}

#[test]
fn gripper_keys_wait_while_the_mission_uses_the_gripper() {
    let mut app = default_app();
    app.handle_key(key("e"), KeyKind::Press, 0.0);
    let mut t = 0.0;
    while !app.pilot().mission().unwrap().holds_gripper() && t < 120.0 {
        t += 0.1;
        app.update(t);
    }
    assert!(
        app.pilot().mission().unwrap().holds_gripper(),
        "a pick-up began"
    );
    app.handle_key(key("c"), KeyKind::Press, t + 0.01);
    assert!(
        app.log_book()
            .iter()
            .any(|e| e.text.contains("the mission is using the gripper"))
    );
}

#[test]
fn in_exploration_the_map_shows_the_places_weighed_and_the_one_it_heads_for() {
    let mut app = default_app();
    app.handle_key(key("e"), KeyKind::Press, 0.0);
    let mut t = 0.0;
    // Step until the mission heads for an exploration target.
    while t < 120.0 {
        t += 0.1;
        app.update(t);
        let heading = (app.pilot().mission())
            .and_then(|m| m.exploration_targets().1)
            .is_some();
        if heading {
            break;
        }
    }
    let mission = app.pilot().mission().expect("a mission");
    let (weighed, heading) = mission.exploration_targets();
    assert!(heading.is_some(), "heading somewhere by {t:.1} s");
    assert!(!weighed.is_empty());
    let screen = common::render(&app);
    assert!(screen.contains('!'), "{screen}");
    // Out of exploration the marks go.
    app.handle_key(key("m"), KeyKind::Press, t);
    assert!(!common::render(&app).contains('!'));
}

#[test]
fn log_prints_every_line_the_mission_logged() {
    let out = navdeck(&["mission", "--seed", "2", "--time-limit", "20", "--log"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("INFO Initial rotation scan"), "{text}");
    assert!(text.contains("mission on "), "the report follows: {text}");
    let json = navdeck(&[
        "mission",
        "--seed",
        "2",
        "--time-limit",
        "20",
        "--log",
        "--json",
    ]);
    let r: Value = serde_json::from_slice(&json.stdout).unwrap();
    assert!(r["log"].as_array().is_some_and(|l| l.len() > 3), "{r}");
    let sweep = navdeck(&["mission", "--sweep", "1..2", "--log"]);
    assert_eq!(sweep.status.code(), Some(2), "one run only");
}

/// Generated worlds where the mission once touched something or gave up: seed 63's rooms
/// (the robot swung off its path at a sharp corner into a block), seed 41's corridors
/// (a block approached from its unmarked side, lost from view three times).
#[test]
fn generated_worlds_that_once_failed_deliver_without_a_touch() {
    for (style, seed) in [("rooms", "63"), ("corridors", "41"), ("boxes", "18")] {
        let r = generated_mission(style, seed, &[]);
        assert_eq!(r["outcome"], "delivered all", "{style} {seed}: {r}");
        assert_eq!(r["collisions"], 0, "{style} {seed}");
    }
}

/// Seed 001's operator takes over mid-mission and hands back: `e` resumes the mission it
/// paused, with its deliveries, the block in the gripper and the map kept.
#[test]
fn taking_over_with_a_block_held_and_pressing_e_resumes_the_mission() {
    let mut app = default_app();
    app.handle_key(key("e"), KeyKind::Press, 0.0);
    let mut t = 0.0;
    let holding = |app: &navdeck::app::App| {
        app.pilot().gripper() == Some(navdeck::data::GripperState::Holding)
    };
    // Wait for the second block in the gripper, so one delivery is behind us.
    while t < 400.0 && app.pilot().mission().unwrap().delivered() < 1 {
        t += 0.1;
        app.update(t);
    }
    while t < 600.0 && !holding(&app) {
        t += 0.1;
        app.update(t);
    }
    assert!(holding(&app), "a second block picked up by {t:.0} s");
    let landmarks = app.pilot().slam().landmark_count();
    // Take over: a drive key stops the mission and drives.
    app.handle_key(key("a"), KeyKind::Press, t + 0.05);
    assert_eq!(app.pilot().mode(), Mode::Manual);
    for _ in 0..30 {
        t += 0.1;
        app.update(t);
    }
    let screen = common::render(&app);
    assert!(screen.contains("paused: e resumes"), "{screen}");
    // Hand back.
    app.handle_key(key("e"), KeyKind::Press, t + 0.05);
    assert_eq!(app.pilot().mode(), Mode::Exploration);
    let mission = app.pilot().mission().unwrap();
    assert_eq!(mission.delivered(), 1, "the first delivery is kept");
    assert!(
        app.pilot().slam().landmark_count() >= landmarks,
        "the map is kept"
    );
    assert!(logged(&app, "Still holding"), "goes on with the held block");
    assert!(logged(&app, "Mission resumed: 1 delivered"));
    let rejected = app.pilot().slam().rejected();
    let mut least = 1;
    while t < 1500.0 && !app.pilot().mission().unwrap().is_done() {
        t += 0.1;
        app.update(t);
        let delivered = app.pilot().mission().unwrap().delivered();
        assert!(delivered >= least, "deliveries never go back");
        least = delivered;
    }
    let mission = app.pilot().mission().unwrap();
    assert!(
        mission.is_done(),
        "finished by {t:.0} s: {}",
        mission.state_label()
    );
    assert_eq!(mission.delivered(), 4);
    let scans = (app.log_book().iter())
        .filter(|e| e.text == "Initial rotation scan")
        .count();
    assert_eq!(scans, 1, "no fresh start");
    assert!(
        app.pilot().slam().rejected() < rejected + 20,
        "sightings are not rejected wholesale after the resume"
    );
}

/// A block put down during a takeover is looked for again, not chased where it was.
#[test]
fn a_block_let_go_during_a_takeover_is_found_again() {
    let mut app = default_app();
    app.handle_key(key("e"), KeyKind::Press, 0.0);
    let mut t = 0.0;
    while t < 400.0 && app.pilot().gripper() != Some(navdeck::data::GripperState::Holding) {
        t += 0.1;
        app.update(t);
    }
    app.handle_key(key("a"), KeyKind::Press, t + 0.05);
    // Open the gripper by hand and back away from the block.
    app.handle_key(key("o"), KeyKind::Press, t + 0.1);
    for _ in 0..30 {
        t += 0.1;
        app.update(t);
    }
    app.handle_key(key("e"), KeyKind::Press, t + 0.05);
    assert!(logged(
        &app,
        "no longer in the gripper - looking for it again"
    ));
    while t < 1500.0 && !app.pilot().mission().unwrap().is_done() {
        t += 0.1;
        app.update(t);
    }
    let mission = app.pilot().mission().unwrap();
    assert_eq!(mission.delivered(), 4, "{}", mission.state_label());
}

/// Picking a block up takes it off the map: the path on to its gate is not reported
/// blocked by the block now in the jaws (it once was, with an identical new path). In the
/// 2 s after a pick-up the held block is within 0.45 m of where it lay (0.2 m/s at most).
#[test]
fn after_a_pick_up_the_held_block_does_not_block_the_path_on() {
    let out = navdeck(&["mission", "--seed", "1", "--log", "--json"]);
    let r: Value = serde_json::from_slice(&out.stdout).unwrap();
    let log: Vec<&str> = r["log"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l.as_str().unwrap())
        .collect();
    let arena = std::fs::read_to_string("maps/arena.toml").unwrap();
    let world = World::from_toml(&arena, Path::new("maps/arena.toml")).unwrap();
    let lay = |id: u32| {
        let block = world.blocks.iter().find(|b| b.markers[0] == id).unwrap();
        (block.pose.x, block.pose.y)
    };
    let time = |line: &str| -> f64 { line.split_whitespace().next().unwrap().parse().unwrap() };
    let number = |text: &str| -> f64 { text.trim_matches(|c| "(),:".contains(c)).parse().unwrap() };
    let picks: Vec<(f64, (f64, f64))> = log
        .iter()
        .filter(|l| l.contains("Picked up"))
        .map(|l| (time(l), lay(l.rsplit(' ').next().unwrap().parse().unwrap())))
        .collect();
    assert_eq!(picks.len(), 4, "{log:#?}");
    for line in log.iter().filter(|l| l.contains("path blocked at")) {
        let (t, words) = (time(line), line.split_whitespace().collect::<Vec<_>>());
        let at = words.iter().position(|w| *w == "at").unwrap();
        let (x, y) = (number(words[at + 1]), number(words[at + 2]));
        for &(p, (bx, by)) in &picks {
            let held = (p..p + 2.0).contains(&t) && (x - bx).hypot(y - by) < 0.45;
            assert!(!held, "the block just picked up blocks the path: {line}");
        }
    }
}

/// Flats with door jambs on the robot's way and markers only every metre: the mission ends
/// without the robot touching a wall, a jamb, a box or a block it is not picking, and every
/// block it counts is at its gate in the twin.
#[test]
fn missions_in_flats_with_door_jambs_and_sparse_markers_touch_nothing() {
    for (world, seed) in [("flat_door_jambs", "31"), ("flat_sparse_markers", "38")] {
        let path = format!("tests/worlds/{world}.toml");
        let out = navdeck(&["mission", "--world", &path, "--seed", seed, "--json"]);
        let r: Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(r["collisions"], 0, "{world}: {}", r["outcome"]);
        assert_eq!(r["delivered"], r["true_delivered"], "{world}");
        assert_eq!(r["outcome"], "delivered all", "{world}");
    }
}
