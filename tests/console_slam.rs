//! What the console shows of lidar SLAM: its rows in the status panel, the pose graph
//! over the map (`G`), and a closed loop flashed in the status panel.

use crate::common;

use common::*;
use navdeck::app::log::FLASH_SECONDS;
use navdeck::app::{App, KeyKind};
use navdeck::pilot::lidar_slam::closure_line;
use navdeck::session::{LinkChoice, LocalizeChoice, SessionSpec};
use navdeck::slam::mcl::config::Estimator;
use navdeck::tui::events::Step;

/// The twin in the built-in arena, mapped by lidar SLAM.
fn slam_app() -> App {
    app_with(SessionSpec {
        world: None,
        seed: 1,
        start: None,
        config: None,
        keymap: None,
        link: LinkChoice::Sim,
        localize: LocalizeChoice {
            estimator: Some(Estimator::Slam),
            map: None,
            initial_pose: None,
        },
    })
}

/// Runs `app` a control period at a time until `limit` seconds of session time or `done`.
fn run_until(app: &mut App, limit: f64, done: impl Fn(&App) -> bool) {
    let mut t = app.now();
    while !done(app) && t < limit {
        t += 0.1;
        app.update(t);
    }
}

fn press_at(app: &mut App, name: &str) {
    let t = app.now();
    app.handle_key(key(name), KeyKind::Press, t);
}

/// The status panel's text (the right-hand panel on a wide screen).
fn status_text(screen: &str, width: u16) -> String {
    let from = usize::from(width - navdeck::app::screen::status_width(width));
    let rows = screen
        .lines()
        .map(|l| l.chars().skip(from).collect::<String>());
    rows.collect::<Vec<_>>().join("\n")
}

/// The map panel's text (left of the status panel).
fn map_text(screen: &str, width: u16) -> String {
    let to = usize::from(width - navdeck::app::screen::status_width(width));
    let rows = screen
        .lines()
        .map(|l| l.chars().take(to).collect::<String>());
    rows.collect::<Vec<_>>().join("\n")
}

/// A short drive: turn, go ahead, turn, go ahead, then `extra`.
fn drive_then(extra: Vec<Step>) -> Vec<Step> {
    let mut steps = hold('a', 0.6);
    steps.extend(hold('w', 3.0));
    steps.extend(hold('d', 1.0));
    steps.extend(hold('w', 2.0));
    steps.extend(extra);
    steps.push(Step::Wait(1.0));
    steps
}

/// After a short drive the status panel says how many keyframes the graph holds, its
/// loops and the last match's response, beside the pose's uncertainty; the graph is
/// off the map until `G` shows it, its nodes as `○`.
#[test]
fn lidar_slam_rows_and_the_pose_graph_after_a_drive_120x40() {
    let plain = run_script(slam_app(), 120, 40, drive_then(Vec::new()));
    let before = screen(&plain.terminal);
    assert!(
        !map_text(&before, 120).contains('○'),
        "off by default: {before}"
    );
    let shown = run_script(slam_app(), 120, 40, drive_then(vec![press('G')]));
    let screen = screen(&shown.terminal);
    let sp = shown.app.pilot().lidar_slam().expect("lidar SLAM runs");
    let keyframes = sp.slam.graph().poses.len();
    assert!(keyframes >= 3, "a drive makes keyframes: {keyframes}");
    let status = status_text(&screen, 120);
    assert!(
        status.contains(&format!("Graph   {keyframes} keyframes, 0 loops")),
        "{screen}"
    );
    assert!(
        status.contains(&format!("Match   response {:.2}", sp.slam.last_response())),
        "{screen}"
    );
    assert!(status.contains("Sigma"), "{screen}");
    let map = map_text(&screen, 120);
    let nodes = map.matches('○').count();
    assert!(nodes >= 2, "the keyframes as nodes: {screen}");
    assert!(
        map.contains(['-', '/', '|', '\\']),
        "edges between them: {screen}"
    );
    insta::assert_snapshot!(screen);
}

/// At 80x24 the lidar SLAM rows fit the narrow status panel with the rows a user needs
/// most.
#[test]
fn lidar_slam_rows_after_a_drive_80x24() {
    let run = run_script(slam_app(), 80, 24, drive_then(Vec::new()));
    let screen = screen(&run.terminal);
    let status = status_text(&screen, 80);
    for label in ["Mode", "Link", "Pose", "Graph"] {
        assert!(status.contains(label), "{label}: {screen}");
    }
    insta::assert_snapshot!(screen);
}

/// Without lidar SLAM there is no graph to show: the key says so and changes nothing.
#[test]
fn the_graph_key_without_lidar_slam_says_why() {
    let mut app = default_app();
    press_at(&mut app, "G");
    assert!(!app.view().graph);
    assert!(logged(&app, "only with lidar SLAM (--estimator slam)"));
}

/// A loop closed while exploring: its line stands highlighted at the top of the status
/// panel, even at 80x24 where the log pane shows four lines, for `FLASH_SECONDS` of
/// session time, then goes (the log keeps it).
#[test]
fn a_closed_loop_is_flashed_in_the_status_panel() {
    let mut app = slam_app();
    press_at(&mut app, "e");
    run_until(&mut app, 300.0, |a| {
        a.pilot()
            .lidar_slam()
            .is_some_and(|s| !s.closures.is_empty())
    });
    let sp = app.pilot().lidar_slam().unwrap();
    let closure = *sp
        .closures
        .last()
        .expect("exploring the arena closes a loop");
    let line = closure_line(&closure);
    // Exploration paused: no other loop closes while the flash runs out.
    press_at(&mut app, "x");
    app.resize(80, 24);
    let screen = render_at(&app, 80, 24);
    let status = status_text(&screen, 80);
    assert!(status.contains("Event   loop closed:"), "{screen}");
    let words: Vec<&str> = line.split_whitespace().collect();
    assert!(words.iter().all(|w| status.contains(w)), "{line}: {screen}");
    insta::assert_snapshot!(screen);
    let closed_at = app.now();
    run_until(&mut app, closed_at + FLASH_SECONDS - 0.2, |_| false);
    assert!(status_text(&render_at(&app, 80, 24), 80).contains("loop closed"));
    run_until(&mut app, closed_at + FLASH_SECONDS + 0.1, |_| false);
    let after = render_at(&app, 80, 24);
    assert!(!status_text(&after, 80).contains("loop closed"), "{after}");
    assert!(logged(&app, &line));
}
