//! Keys that must not surprise: teleop_twist_keyboard's layout (`q` raises the speeds,
//! it does not quit), the help overlay (any key closes it and does nothing else, its
//! lines say what a key does in the mode), `?` in a replay, a held key in a refusing
//! state (one log line, not one per repeat), and errors in words a user reads.

use crate::common;

use common::*;
use navdeck::app::mode::Mode;
use navdeck::app::{App, KeyKind};
use navdeck::session::{Session, SessionSpec};
use navdeck::tui::events::Step;
use navdeck::tui::run::Exit;

/// The teleop_twist_keyboard layout, as `--keymap keymaps/teleop_twist_keyboard.toml`
/// loads it (the path relative to the package, as the help's title shows it).
fn teleop_app() -> App {
    app_with(SessionSpec {
        keymap: Some("keymaps/teleop_twist_keyboard.toml".into()),
        ..SessionSpec::twin(None)
    })
}

/// The default session with an arm (`[arm]` in the config), for gripper mode.
fn arm_app() -> App {
    let dir = scratch(&format!("arm-{:?}", std::thread::current().id()));
    let config = dir.join("arm.toml");
    std::fs::write(&config, "[arm]\n").unwrap();
    Session::load(&SessionSpec {
        config: Some(config),
        ..SessionSpec::twin(None)
    })
    .unwrap()
    .into_app(0.0)
}

/// Presses the key named `name` at `t`.
fn tap(app: &mut App, name: &str, t: f64) {
    app.handle_key(key(name), KeyKind::Press, t);
}

/// Types `:line` and enter at `t`.
fn command(app: &mut App, line: &str, t: f64) {
    tap(app, ":", t);
    for c in line.chars() {
        app.handle_key(navdeck::keymap::Key::char(c), KeyKind::Press, t);
    }
    tap(app, "enter", t);
}

/// The linear and angular speeds the drive keys ask for.
fn speeds(app: &App) -> (f64, f64) {
    let t = app.pilot().teleop();
    (t.linear_speed, t.angular_speed)
}

fn log_text(app: &App) -> String {
    let lines: Vec<String> = (app.log_book().iter())
        .map(|e| format!("{} ×{}", e.text, e.repeats))
        .collect();
    lines.join("\n")
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

#[test]
fn teleop_layout_q_raises_the_speeds_and_the_console_keeps_running() {
    let app = teleop_app();
    let (v0, w0) = speeds(&app);
    // The first landmarks are logged while the console settles; then q twice.
    let steps = vec![Step::Wait(1.0), press('q'), press('q'), Step::Wait(0.1)];
    let out = run_script(app, 120, 40, steps);
    assert_ne!(out.exit, Exit::Quit, "q did not quit");
    assert!(!out.app.should_quit());
    let (v, w) = speeds(&out.app);
    assert!(close(v, v0 * 1.1f64.powi(2)), "{v0} -> {v}");
    assert!(close(w, w0 * 1.1f64.powi(2)), "{w0} -> {w}");
    // teleop_twist_keyboard's speed line, the two presses as one line ×2.
    let said = (out.app.log_book().iter())
        .filter(|e| e.text.starts_with("currently: speed"))
        .last()
        .unwrap();
    assert_eq!(
        said.text,
        format!("currently: speed {v:.2} m/s turn {w:.2} rad/s"),
        "{}",
        log_text(&out.app)
    );
    assert_eq!(said.repeats, 2, "{}", log_text(&out.app));
    let screen = common::screen(&out.terminal);
    assert!(
        screen.contains("currently: speed 0.18 m/s turn 1.82 rad/s ×2"),
        "{screen}"
    );
}

#[test]
fn teleop_layout_z_lowers_all_speeds_w_x_the_linear_only_e_c_the_turn_rate_only() {
    let mut app = teleop_app();
    let (v0, w0) = speeds(&app);
    tap(&mut app, "z", 0.1);
    assert!(close(speeds(&app).0, v0 / 1.1) && close(speeds(&app).1, w0 / 1.1));
    let (v1, w1) = speeds(&app);
    tap(&mut app, "w", 0.2);
    assert!(close(speeds(&app).0, v1 * 1.1) && close(speeds(&app).1, w1));
    tap(&mut app, "x", 0.3);
    tap(&mut app, "x", 0.4);
    assert!(close(speeds(&app).0, v1 / 1.1) && close(speeds(&app).1, w1));
    let v2 = speeds(&app).0;
    tap(&mut app, "e", 0.5);
    assert!(close(speeds(&app).0, v2) && close(speeds(&app).1, w1 * 1.1));
    tap(&mut app, "c", 0.6);
    tap(&mut app, "c", 0.7);
    assert!(close(speeds(&app).0, v2) && close(speeds(&app).1, w1 / 1.1));
    // e and c changed speeds only: still manual mode, nothing held, nothing stopped.
    assert_eq!(app.pilot().mode(), Mode::Manual);
    assert!(!app.should_quit());
}

#[test]
fn teleop_layout_q_never_quits_but_ctrl_c_and_colon_quit_do() {
    let mut app = teleop_app();
    tap(&mut app, "t", 0.1);
    assert_eq!(app.pilot().mode(), Mode::Thinking);
    let before = speeds(&app).0;
    tap(&mut app, "q", 0.2);
    assert!(
        !app.should_quit(),
        "q in thinking mode does not quit either"
    );
    assert!(speeds(&app).0 > before);
    tap(&mut app, "ctrl-c", 0.3);
    assert!(app.should_quit(), "ctrl-c quits");

    for line in ["quit", "q"] {
        let mut app = teleop_app();
        command(&mut app, line, 0.1);
        assert!(app.should_quit(), ":{line} quits");
        assert!(logged(&app, "robot stopped: quit by user"));
    }
}

#[test]
fn teleop_layout_title_and_help_say_how_to_quit() {
    let mut app = teleop_app();
    app.resize(120, 40);
    let screen = render_at(&app, 120, 40);
    assert!(screen.contains("? help  ctrl-c quit"), "{screen}");
    assert!(!screen.contains("q quit"), "{screen}");
    tap(&mut app, "?", 0.1);
    let help = render_at(&app, 120, 40);
    assert!(help.contains("ctrl-c"), "{help}");
    assert!(help.contains("stop and quit (also :quit)"), "{help}");
    assert!(help.contains("] q [ z  all speeds +/-10 %"), "{help}");
    assert!(help.contains("e c      turn rate +/-10 %"), "{help}");
    insta::assert_snapshot!("teleop_help_120x40", help);
    // The default layout's title still names q.
    let default = render_at(&default_app(), 120, 40);
    assert!(default.contains("? help  q quit"), "{default}");
}

#[test]
fn with_help_open_any_key_closes_it_and_does_nothing_else() {
    let mut app = default_app();
    let start = app.true_pose().unwrap();
    let mut t = 0.0;
    for name in ["w", "d", "q", "space", "e", "x"] {
        t += 0.1;
        tap(&mut app, "?", t);
        assert!(app.view().help, "? opens the help");
        t += 0.1;
        tap(&mut app, name, t);
        assert!(!app.view().help, "{name} closes the help");
        for _ in 0..5 {
            t += 0.1;
            app.update(t);
        }
        assert!(!app.should_quit(), "{name} did not quit");
        assert!(!app.pilot().estop(), "{name} did not e-stop");
        assert_eq!(app.pilot().mode(), Mode::Manual, "{name}");
        assert!(app.held_keys().is_empty(), "{name} drives nothing");
    }
    let end = app.true_pose().unwrap();
    let moved = (end.x - start.x).hypot(end.y - start.y);
    assert!(moved < 1e-6, "the robot did not move ({moved} m)");
    tap(&mut app, "?", t + 0.1);
    let help = render_at(&app, 120, 40);
    assert!(help.contains("any key closes"), "{help}");
    assert!(!help.contains("any other key"), "{help}");
}

#[test]
fn help_says_what_the_speed_keys_do_in_gripper_mode() {
    let mut app = arm_app();
    tap(&mut app, "?", 0.1);
    let manual = render_at(&app, 120, 40);
    assert!(manual.contains("all speeds +/-10 %"), "{manual}");
    tap(&mut app, "?", 0.2);
    tap(&mut app, "h", 0.3);
    assert_eq!(app.pilot().mode(), Mode::Gripper);
    tap(&mut app, "?", 0.4);
    for (w, h) in [(80, 24), (120, 40), (240, 60)] {
        app.resize(w, h);
        let help = render_at(&app, w, h);
        assert!(help.contains("] ["), "{help}");
        assert!(help.contains("arm jog speed +/-10 %"), "{help}");
        assert!(!help.contains("all speeds"), "{help}");
        insta::assert_snapshot!(format!("gripper_help_{w}x{h}"), help);
    }
    // And the key does what the help says.
    tap(&mut app, "?", 0.5);
    let before = speeds(&app);
    tap(&mut app, "]", 0.6);
    assert_eq!(speeds(&app), before, "the drive speeds stay");
    assert!(logged(&app, "arm jog"), "{}", log_text(&app));
}

// ----- held keys in refusing states -----

/// Holds `name` as a terminal without release events does: a press every 1/30 s,
/// `repeats` times from `t`, the console running in between. Returns the time after.
fn hold_key(app: &mut App, name: &str, t: f64, repeats: usize) -> f64 {
    let mut t = t;
    for _ in 0..repeats {
        tap(app, name, t);
        t += 1.0 / 30.0;
        app.update(t);
    }
    t
}

/// The log's lines (a collapsed run counting once) added while `name` is held 50 times.
fn lines_added_holding(app: &mut App, name: &str, t: f64) -> (usize, String) {
    let before = app.log_book().iter().count();
    hold_key(app, name, t, 50);
    let added = app.log_book().iter().count() - before;
    (added, log_text(app))
}

#[test]
fn a_held_key_with_the_emergency_stop_on_adds_one_line_not_fifty() {
    let mut app = default_app();
    // The first landmarks are logged first.
    for k in 1..=20 {
        app.update(0.1 * f64::from(k));
    }
    let t = 2.0;
    tap(&mut app, "space", t);
    assert!(app.pilot().estop());
    let (added, log) = lines_added_holding(&mut app, "w", t + 0.1);
    assert!(added <= 2, "{added} lines:\n{log}");
    let last = app.log_book().last().unwrap();
    assert!(last.text.starts_with("emergency stop is on"), "{log}");
    assert_eq!(last.repeats, 50, "{log}");
    assert!(render_at(&app, 120, 40).contains("×50"));
}

/// A link whose robot never answers.
struct SilentLink;

impl navdeck::link::RobotLink for SilentLink {
    fn label(&self) -> String {
        "silent".into()
    }
    fn send(&mut self, _: &navdeck::link::Command) -> Result<(), navdeck::link::LinkError> {
        Ok(())
    }
    fn poll(&mut self, _: f64) -> Result<navdeck::link::SensorFrame, navdeck::link::LinkError> {
        Err(navdeck::link::LinkError::Lost(
            "waiting for odometry on /odom (2.0 s): nothing publishes it in domain 0 \
             (1 other participants)"
                .into(),
        ))
    }
    fn stop(&mut self) {}
}

#[test]
fn a_held_key_with_the_link_lost_adds_one_short_line_not_fifty() {
    let config = navdeck::config::Config::default();
    let keymap = navdeck::keymap::Keymap::default_map();
    let mut app = App::new(config, keymap, Box::new(SilentLink), 0.0);
    app.update(0.3);
    assert!(matches!(
        app.pilot().link_status(),
        navdeck::app::LinkStatus::Lost(_)
    ));
    let (added, log) = lines_added_holding(&mut app, "w", 0.4);
    assert!(added <= 2, "{added} lines:\n{log}");
    let last = app.log_book().last().unwrap();
    assert_eq!(last.text, "forward: nothing moves while the link is lost");
    assert_eq!(last.repeats, 50);
    // One line at 80 columns: the log pane's inner width less the timestamp and level.
    let line = format!("00:00.0 WARN {} ×50", last.text);
    assert!(line.chars().count() <= 78, "{line}");
    let screen = render_at(&app, 80, 24);
    assert!(
        screen.contains("forward: nothing moves while the link is lost ×50"),
        "{screen}"
    );
}

#[test]
fn a_held_arm_key_at_the_edge_of_the_reach_adds_one_line_not_fifty() {
    let mut app = arm_app();
    tap(&mut app, "h", 0.1);
    tap(&mut app, "2", 0.2);
    let mut t = 0.2;
    for _ in 0..20 {
        t += 0.1;
        app.update(t);
    }
    // Out to the edge, then on against it.
    let t = hold_key(&mut app, "w", t, 180);
    assert!(logged(&app, "arm stops at the edge"), "{}", log_text(&app));
    let (added, log) = lines_added_holding(&mut app, "w", t);
    assert!(added <= 2, "{added} lines:\n{log}");
}

// ----- words -----

#[test]
fn a_gripper_key_is_told_once_in_one_phrasing_then_what_the_gripper_does() {
    let mut app = default_app();
    // o opens the gripper in every mode; c closes it outside manual mode.
    tap(&mut app, "o", 0.1);
    for k in 2..40 {
        app.update(0.1 * f64::from(k));
    }
    let log = log_text(&app);
    assert!(logged(&app, "gripper asked to open"), "{log}");
    assert!(!logged(&app, "opening gripper"), "{log}");
    tap(&mut app, "t", 4.2);
    tap(&mut app, "c", 4.3);
    for k in 44..80 {
        app.update(0.1 * f64::from(k));
    }
    let log = log_text(&app);
    assert!(logged(&app, "gripper asked to close"), "{log}");
    assert!(logged(&app, "gripper closing"), "{log}");
    assert!(!logged(&app, "closing gripper"), "{log}");
}

#[test]
fn the_console_without_a_terminal_says_so_not_the_os_error() {
    // Output captured, input empty: no terminal at all.
    let out = navdeck(&[]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("navdeck's console needs a terminal"), "{err}");
    assert!(err.contains("--headless"), "{err}");
    assert!(!err.to_lowercase().contains("typewriter"), "{err}");
    assert!(!err.contains("os error"), "{err}");
}

#[test]
fn a_bad_whole_number_on_the_command_line_names_the_option_and_value() {
    let cases: [(&[&str], &str, &str); 4] = [
        (&["--seed", "12x", "--headless"], "--seed", "12x"),
        (&["--seed", "-1", "--headless"], "--seed", "-1"),
        (
            &["world", "generate", "--seed", "1", "--blocks", "two"],
            "--blocks",
            "two",
        ),
        (&["--domain", "one", "--link", "ros2"], "--domain", "one"),
    ];
    for (args, option, value) in cases {
        let out = navdeck(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!err.contains("invalid digit"), "{args:?}: {err}");
        assert!(err.contains(option), "{args:?}: {err}");
        assert!(
            err.contains(&format!("`{value}` is not a")),
            "{args:?}: {err}"
        );
    }
}

#[test]
fn a_map_that_cannot_be_a_world_is_one_sentence_naming_the_file_and_why() {
    let out = navdeck(&["--world", "tests/maps/nothere.yaml", "--headless"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains(
            "cannot use map tests/maps/nothere.yaml as a world: cannot read it: there is no \
             such file"
        ),
        "{err}"
    );
    assert!(!err.contains("world tests/maps"), "not nested: {err}");
    assert!(!err.contains("os error"), "{err}");
}

// ----- the replay -----

/// A few seconds of driving the built-in arena, recorded (made once per test binary).
fn short_recording() -> std::path::PathBuf {
    static MADE: std::sync::OnceLock<std::path::PathBuf> = std::sync::OnceLock::new();
    MADE.get_or_init(|| {
        let path = scratch("replay").join("drive.mcap");
        let mut app = default_app();
        navdeck::console::start_recording(&mut app, &path, Default::default(), true).unwrap();
        let keys: Vec<_> = "wwwwwwwwdddd"
            .chars()
            .map(navdeck::keymap::Key::char)
            .collect();
        navdeck::runners::headless::run(&mut app, &keys, 10.0);
        app.finish_recording().unwrap().unwrap();
        path
    })
    .clone()
}

/// Plays the short recording, paused at its start, in a 120x40 test terminal through
/// `steps`: the screen, whether the help is open, and how the loop ended.
fn replay(steps: Vec<Step>) -> (String, bool, Exit) {
    use navdeck::replay::playback::View;
    let recorded = std::sync::Arc::new(navdeck::replay::load(&short_recording()).unwrap());
    let (screen, player, exit) =
        common::replay_played(recorded, View::AsRecorded, true, (120, 40), steps);
    (screen, player.playback.help, exit)
}

#[test]
fn question_mark_in_a_replay_shows_its_keys_and_any_key_closes_them() {
    let (text, open, _) = replay(vec![press('?'), Step::Wait(0.1)]);
    assert!(open);
    assert!(text.contains("Replay keys: any key closes"), "{text}");
    assert!(text.contains("play or pause"), "{text}");
    insta::assert_snapshot!("replay_help_120x40", text);
    // q closes the help and does not quit; the next q does.
    let (text, open, exit) = replay(vec![press('?'), press('q'), Step::Wait(0.1)]);
    assert!(!open);
    assert_ne!(exit, Exit::Quit, "{text}");
    assert!(!text.contains("Replay keys"), "{text}");
    let (_, _, exit) = replay(vec![press('?'), press('q'), press('q')]);
    assert_eq!(exit, Exit::Quit);
}
