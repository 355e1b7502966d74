//! Thinking and path-following modes as a user meets them: plan by cursor or command,
//! follow to "Destination arrived", refuse impossible goals, replan, and give control back.

use crate::common;

use common::{app_with, default_app, key, logged, run_script, screen};
use navdeck::app::App;
use navdeck::app::KeyKind;
use navdeck::app::mode::Mode;
use navdeck::keymap::parse_key_sequence;
use navdeck::runners::headless;
use navdeck::session::{LinkChoice, SessionSpec};
use navdeck::tui::events::Step;
use std::path::PathBuf;

fn world_app(file: &str) -> App {
    app_with(SessionSpec {
        world: Some(PathBuf::from("tests/worlds").join(file)),
        seed: 1,
        start: None,
        config: None,
        keymap: None,
        link: LinkChoice::Sim,
        localize: Default::default(),
    })
}

/// Plays `keys` headless and returns the report.
fn play(app: &mut App, keys: &str) -> headless::Report {
    headless::run(app, &parse_key_sequence(keys).unwrap(), 10.0)
}

#[test]
fn thinking_mode_plans_to_the_cursor_and_the_robot_stays_put() {
    let mut app = default_app();
    let start = app.true_pose().unwrap();
    let report = play(&mut app, "t<right><right><right><right><right>kkkk<enter>");
    let route = app.pilot().route().expect("a path was planned");
    assert!(route.plan.length > 0.2, "{}", route.plan.length);
    assert!(logged(&app, "path to ("), "log: plan time, length and cost");
    assert_eq!(app.pilot().mode(), Mode::Thinking);
    let end = report.travel.true_pose.unwrap();
    assert!((end.x - start.x).abs() < 1e-6 && (end.y - start.y).abs() < 1e-6);
    assert!(app.goal_cursor().is_some());
}

#[test]
fn goto_then_p_follows_to_destination_arrived() {
    let mut app = default_app();
    let report = play(&mut app, ":goto 0.9 0.6<enter>p");
    assert!(report.following.arrived, "warnings: {:?}", report.warnings);
    assert!(logged(&app, "Destination arrived"));
    let p = report.travel.true_pose.unwrap();
    assert!((p.x - 0.9).hypot(p.y - 0.6) < 0.08, "ended at {p:?}");
    assert_eq!(report.collisions, Some(0));
    // The hybrid controller (the default) keeps within seed 004's curve error, and better.
    assert!(report.following.true_cross_track_rms.unwrap() < 0.03);
    // Stopped at the end.
    assert!(app.pilot().commanded().is_zero());
}

#[test]
fn goto_marker_approaches_a_landmark_on_the_map() {
    let mut app = default_app();
    // Marker 311 is on the face of box 3 that looks at the robot's start: seen at once.
    let report = play(&mut app, ":goto marker 311<enter>p");
    assert!(report.following.arrived, "warnings: {:?}", report.warnings);
    let marker = app.pilot().slam().landmark(311).unwrap().mean;
    let p = report.travel.true_pose.unwrap();
    let d = (p.x - marker.x).hypot(p.y - marker.y);
    assert!(
        (0.1..0.3).contains(&d),
        "stopped {d:.2} m from the marker: {p:?}"
    );
    assert_eq!(report.collisions, Some(0));
}

#[test]
fn a_goal_inside_an_obstacle_is_refused_and_the_robot_does_not_move() {
    let mut app = default_app();
    let start = app.true_pose().unwrap();
    // The middle of box 3, whose faces the robot sees from its start.
    let report = play(&mut app, ":goto 0.6 -0.9<enter>p");
    assert!(
        logged(&app, "no path to (0.60, -0.90): goal"),
        "{:?}",
        report.warnings
    );
    assert!(logged(&app, "inside an obstacle"));
    assert!(logged(&app, "no path to follow"));
    assert_ne!(app.pilot().mode(), Mode::PathFollowing);
    let end = report.travel.true_pose.unwrap();
    assert!((end.x - start.x).hypot(end.y - start.y) < 1e-6);
}

#[test]
fn an_unknown_marker_or_a_bad_command_is_named_in_the_log() {
    let mut app = default_app();
    play(
        &mut app,
        ":goto marker 999<enter>:fly 1 2<enter>:goto 1 north<enter>",
    );
    assert!(logged(&app, "marker 999: it is not on the map yet"));
    assert!(logged(&app, "unknown command `fly`"));
    assert!(logged(&app, "`north` is not a number"));
    assert!(app.pilot().route().is_none());
}

#[test]
fn a_path_blocked_by_a_newly_seen_obstacle_is_replanned() {
    let mut app = world_app("hidden_box.toml");
    let report = play(&mut app, ":goto 1.5 0.0<enter>p");
    assert!(report.following.arrived, "warnings: {:?}", report.warnings);
    assert!(logged(&app, "path blocked at"), "{:?}", report.warnings);
    assert_eq!(report.collisions, Some(0));
}

#[test]
fn a_drive_key_takes_control_back_at_once() {
    let mut app = default_app();
    play(&mut app, ":goto 0.9 0.6<enter>");
    let t = app.now();
    app.handle_key(key("p"), KeyKind::Press, t);
    for k in 1..=20 {
        app.update(t + 0.1 * f64::from(k));
    }
    assert_eq!(app.pilot().mode(), Mode::PathFollowing);
    assert!(app.pilot().commanded().linear > 0.05, "following");
    app.handle_key(key("s"), KeyKind::Press, t + 2.05);
    assert_eq!(app.pilot().mode(), Mode::Manual);
    assert!(
        app.pilot().commanded().linear < 0.0,
        "s drives backward at once"
    );
    assert!(logged(&app, "manual control taken back"));
}

#[test]
fn space_and_a_mode_change_stop_following_at_once() {
    for stop_key in ["<space>", "m", "t"] {
        let mut app = default_app();
        play(&mut app, ":goto 0.9 0.6<enter>");
        let t = app.now();
        app.handle_key(key("p"), KeyKind::Press, t);
        for k in 1..=20 {
            app.update(t + 0.1 * f64::from(k));
        }
        assert!(app.pilot().commanded().linear > 0.05);
        let k = parse_key_sequence(stop_key).unwrap()[0];
        app.handle_key(k, KeyKind::Press, t + 2.05);
        assert!(
            app.pilot().commanded().is_zero(),
            "{stop_key} stops the robot"
        );
        assert_ne!(app.pilot().mode(), Mode::PathFollowing);
    }
}

#[test]
fn the_controller_is_chosen_by_key_and_by_command() {
    let mut app = default_app();
    assert_eq!(app.pilot().follower().controller().name(), "hybrid");
    play(&mut app, "tn");
    assert_eq!(app.pilot().follower().controller().name(), "pid");
    play(&mut app, ":controller pure_pursuit<enter>");
    assert_eq!(app.pilot().follower().controller().name(), "pure_pursuit");
    assert!(logged(&app, "path controller: Pure pursuit"));
}

#[test]
fn each_controller_reaches_the_goal_without_touching_anything() {
    for controller in ["pid", "pure_pursuit", "hybrid"] {
        let mut app = default_app();
        let report = play(
            &mut app,
            &format!(":controller {controller}<enter>:goto 1.2 1.2<enter>p"),
        );
        assert!(
            report.following.arrived,
            "{controller}: {:?}",
            report.warnings
        );
        assert_eq!(report.collisions, Some(0), "{controller}");
    }
}

#[test]
fn the_screen_shows_the_path_goal_and_progress() {
    let mut steps: Vec<Step> = ":goto 0.9 0.6".chars().map(common::press).collect();
    steps.push(Step::Event(navdeck::tui::events::Event::Key(
        key("enter"),
        KeyKind::Press,
    )));
    steps.push(common::press('p'));
    steps.push(Step::Wait(3.0));
    steps.push(common::press('q'));
    let out = run_script(default_app(), 100, 30, steps);
    let text = screen(&out.terminal);
    assert!(text.contains('•'), "path drawn:\n{text}");
    assert!(text.contains('G'), "goal drawn:\n{text}");
    assert!(
        text.contains(" s left"),
        "progress in the status panel:\n{text}"
    );
    assert!(text.contains("XTE"), "cross-track error:\n{text}");
}

#[test]
fn the_command_line_shows_what_is_typed() {
    let steps: Vec<Step> = ":goto 1".chars().map(common::press).collect();
    let out = run_script(default_app(), 100, 30, steps);
    assert!(screen(&out.terminal).contains(":goto 1█"));
}
