//! The console's behaviour as a user at the keyboard sees it, on the digital twin.

use crate::common;

use common::*;
use navdeck::app::mode::Mode;
use navdeck::app::{App, KeyKind};
use navdeck::data::GripperState;
use navdeck::keymap::Key;
use navdeck::tui::events::Step;
use navdeck::tui::run::Exit;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Steps the console through `seconds` of session time with no input.
fn idle(app: &mut App, seconds: f64) {
    let end = app.now() + seconds;
    while app.now() < end - 1e-9 {
        let t = (app.now() + 0.01).min(end);
        app.update(t);
    }
}

fn last_log(app: &App) -> &str {
    &app.log_book().last().expect("a log line").text
}

fn true_speed(app: &App) -> f64 {
    app.link().ground_truth().unwrap().velocity().linear
}

#[test]
fn holding_w_drives_forward_and_robot_rests_within_deadman_of_last_key() {
    let mut app = default_app();
    let start = app.true_pose().unwrap();
    let mut t = 0.0;
    // Auto-repeat at 30 Hz for 2 s, as a terminal without release events sends it.
    while t < 2.0 {
        app.handle_key(Key::char('w'), KeyKind::Press, t);
        t += 1.0 / 30.0;
        app.update(t);
        assert!(
            app.pilot().commanded().linear > 0.0,
            "command dropped at {t:.3} s"
        );
    }
    let last_key = t - 1.0 / 30.0;
    let moved = app.true_pose().unwrap();
    let heading = (start.theta.cos(), start.theta.sin());
    let forward = (moved.x - start.x) * heading.0 + (moved.y - start.y) * heading.1;
    assert!(forward > 0.2, "drove only {forward:.3} m forward");
    let wait = last_key + 0.5 - app.now();
    idle(&mut app, wait);
    assert!(
        true_speed(&app).abs() < 1e-9,
        "still moving 0.5 s after the key"
    );
    let rest = app.true_pose().unwrap();
    idle(&mut app, 2.0);
    let later = app.true_pose().unwrap();
    assert!((later.x - rest.x).abs() < 1e-9 && (later.y - rest.y).abs() < 1e-9);
}

#[test]
fn a_single_tap_moves_a_little_then_stops() {
    let mut app = default_app();
    let start = app.true_pose().unwrap();
    app.handle_key(Key::char('w'), KeyKind::Press, 0.0);
    idle(&mut app, 3.0);
    let end = app.true_pose().unwrap();
    let d = ((end.x - start.x).powi(2) + (end.y - start.y).powi(2)).sqrt();
    assert!(d > 0.01 && d < 0.1, "a tap moved {d:.3} m");
    assert_eq!(true_speed(&app), 0.0);
}

#[test]
fn release_event_stops_at_once_in_kitty_terminals() {
    let mut app = default_app();
    // A kitty terminal has sent a release before: from then on releases are trusted.
    app.handle_key(Key::char('d'), KeyKind::Release, 0.0);
    app.handle_key(Key::char('w'), KeyKind::Press, 0.0);
    idle(&mut app, 0.6);
    // No repeat yet after 0.6 s: with release events the key is still held.
    assert!(app.pilot().commanded().linear > 0.0);
    app.handle_key(Key::char('w'), KeyKind::Release, 0.6);
    assert_eq!(app.pilot().commanded().linear, 0.0);
}

#[test]
fn space_is_an_emergency_stop_and_only_space_again_releases_it() {
    let mut app = default_app();
    for i in 0..10 {
        app.handle_key(Key::char('w'), KeyKind::Press, f64::from(i) * 0.05);
    }
    app.update(0.5);
    assert!(true_speed(&app) > 0.0);
    app.handle_key(key("space"), KeyKind::Press, 0.5);
    assert!(app.pilot().estop());
    assert_eq!(app.pilot().commanded().linear, 0.0);
    idle(&mut app, 0.3);
    assert_eq!(true_speed(&app), 0.0);
    assert!(
        app.log_book()
            .iter()
            .any(|e| e.text.contains("EMERGENCY STOP"))
    );
    // A drive key neither releases it nor drives.
    app.handle_key(Key::char('w'), KeyKind::Press, app.now());
    assert!(app.pilot().estop() && app.pilot().commanded().linear == 0.0);
    assert!(
        app.log_book()
            .iter()
            .any(|e| e.text.contains("press it again (space) to release"))
    );
    // Space again releases it, and the robot stays still until driven.
    app.handle_key(key("space"), KeyKind::Press, app.now());
    assert!(!app.pilot().estop() && app.pilot().commanded().linear == 0.0);
    app.handle_key(Key::char('w'), KeyKind::Press, app.now());
    assert!(app.pilot().commanded().linear > 0.0);
}

#[test]
fn a_key_that_closes_the_help_does_nothing_else() {
    let mut app = default_app();
    app.handle_key(key("?"), KeyKind::Press, 0.0);
    app.handle_key(key("e"), KeyKind::Press, 0.1);
    assert_eq!(
        app.pilot().mode(),
        navdeck::app::mode::Mode::Manual,
        "e only closed the help"
    );
    app.handle_key(key("e"), KeyKind::Press, 0.2);
    assert_eq!(app.pilot().mode(), navdeck::app::mode::Mode::Exploration);
}

#[test]
fn follow_mode_without_a_path_says_so_and_changes_nothing() {
    let mut app = default_app();
    app.handle_key(Key::char('p'), KeyKind::Press, 0.0);
    assert_eq!(app.pilot().mode(), Mode::Manual);
    let said: Vec<&str> = app.log_book().iter().map(|e| e.text.as_str()).collect();
    assert!(
        said.iter().any(|l| l.starts_with("no path to follow")),
        "p without a path says so: {said:?}"
    );
}

#[test]
fn gripper_keys_open_and_close_the_twins_gripper() {
    let mut app = default_app();
    app.handle_key(Key::char('o'), KeyKind::Press, 0.0);
    idle(&mut app, 2.0);
    assert_eq!(app.pilot().gripper(), Some(GripperState::Open));
    // In manual mode `c` stops (seed 001); the gripper closes from other bindings only.
    app.handle_key(Key::char('c'), KeyKind::Press, app.now());
    idle(&mut app, 2.0);
    assert_eq!(app.pilot().gripper(), Some(GripperState::Open));
}

#[test]
fn speed_keys_change_the_drive_speed_within_limits() {
    let mut app = default_app();
    let before = app.pilot().teleop().linear_speed;
    app.handle_key(Key::char(']'), KeyKind::Press, 0.0);
    assert!(app.pilot().teleop().linear_speed > before);
    for _ in 0..50 {
        app.handle_key(Key::char(']'), KeyKind::Press, 0.0);
    }
    let (max_v, max_w) = app.pilot().teleop().limits();
    assert_eq!(app.pilot().teleop().linear_speed, max_v);
    assert_eq!(app.pilot().teleop().angular_speed, max_w);
    assert!(
        app.log_book()
            .iter()
            .any(|e| e.text.contains("already at their limit"))
    );
}

#[test]
fn quit_stops_the_robot_and_ends_the_loop() {
    let mut steps = hold('w', 1.0);
    steps.push(press('q'));
    steps.push(Step::Wait(5.0));
    let s = run_script(default_app(), 80, 24, steps);
    assert_eq!(s.exit, Exit::Quit);
    assert_eq!(s.app.pilot().commanded().linear, 0.0);
    assert!(
        last_log(&s.app).contains("quit by user"),
        "{}",
        last_log(&s.app)
    );
}

#[test]
fn a_signal_stops_the_robot_and_ends_the_loop() {
    let signal = AtomicUsize::new(0);
    let mut app = default_app();
    app.handle_key(Key::char('w'), KeyKind::Press, 0.0);
    signal.store(15, Ordering::SeqCst);
    let s = run_script_with_signal(app, 80, 24, hold('w', 1.0), &signal);
    assert_eq!(s.exit, Exit::Signal(15));
    assert_eq!(s.app.link().ground_truth().unwrap().command().linear, 0.0);
    assert!(last_log(&s.app).contains("SIGTERM"), "{}", last_log(&s.app));
    assert_eq!(s.app.pilot().commanded().linear, 0.0);
}

#[test]
fn closed_input_stops_the_robot() {
    let s = run_script(default_app(), 80, 24, hold('w', 0.5));
    assert_eq!(s.exit, Exit::InputClosed);
    assert!(
        last_log(&s.app).contains("input closed"),
        "{}",
        last_log(&s.app)
    );
}

#[test]
fn a_panic_still_stops_the_robot() {
    let (app, link) = recording_app();
    let stops = link.stops.clone();
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(move || {
        let mut app = app;
        app.handle_key(Key::char('w'), KeyKind::Press, 0.0);
        app.update(0.2);
        panic!("a bug somewhere in the console");
    }));
    assert!(result.is_err());
    assert!(*stops.lock().unwrap() >= 1, "the link was not told to stop");
}

#[test]
fn idle_console_redraws_about_once_a_second_and_driving_more() {
    let idle = run_script(default_app(), 80, 24, vec![Step::Wait(10.0)]);
    assert!(
        idle.stats.frames_drawn <= 12,
        "idle drew {} frames in 10 s",
        idle.stats.frames_drawn
    );
    let driving = run_script(default_app(), 80, 24, hold('w', 3.0));
    assert!(
        driving.stats.frames_drawn >= 20,
        "driving drew only {} frames in 3 s",
        driving.stats.frames_drawn
    );
}

#[test]
fn help_overlay_lists_the_active_modes_bindings() {
    let s = run_script(default_app(), 120, 40, vec![press('?'), Step::Wait(0.2)]);
    let text = screen(&s.terminal);
    assert!(text.contains("Keys in manual mode"), "{text}");
    assert!(text.contains("w s a d  drive, while held"), "{text}");
    assert!(text.contains("emergency stop"), "{text}");
    assert!(text.contains("(the deadman)"), "{text}");
}

#[test]
fn status_panel_shows_mode_link_pose_and_velocities() {
    let s = run_script(default_app(), 100, 30, hold('w', 1.0));
    let text = screen(&s.terminal);
    for label in [
        "MANUAL", "sim:", "Pose", "Cmd", "Meas", "Speed", "Loop", "10 Hz",
    ] {
        assert!(text.contains(label), "missing {label:?} in\n{text}");
    }
}

#[test]
fn driving_into_a_wall_stops_short_and_without_the_monitor_is_a_logged_collision() {
    // From the start pose facing east, turn right to face the south wall and drive on.
    let plan = [('d', 1.1), ('w', 6.0)];
    let mut app = default_app();
    hold_in_turn(&mut app, &plan, 0.0);
    assert_eq!(app.link().ground_truth().unwrap().collisions(), 0);
    let said = |app: &App, start: &str| app.log_book().iter().any(|e| e.text.starts_with(start));
    assert!(said(&app, "behaviour: collision monitor (was teleop)"));
    // Held at the wall, the monitor has control and its zones are drawn round the robot
    // (zoomed in, where they span several cells).
    let t = hold_in_turn(&mut app, &[('w', 0.2)], 7.2);
    for _ in 0..3 {
        app.handle_key(Key::char('+'), KeyKind::Press, t);
    }
    let screen = render(&app);
    let outline = screen
        .lines()
        .take(24)
        .map(|l| l.matches('!').count())
        .sum::<usize>();
    assert!(outline >= 4, "no zone outline on the map:\n{screen}");
    // With the monitor switched off, the same drive touches the wall and says so.
    let mut app = default_app();
    for c in ":behaviour collision_monitor off".chars() {
        app.handle_key(key(&c.to_string()), KeyKind::Press, 0.0);
    }
    app.handle_key(key("enter"), KeyKind::Press, 0.0);
    hold_in_turn(&mut app, &plan, 0.0);
    assert!(app.link().ground_truth().unwrap().collisions() >= 1);
    assert!(said(&app, "collision at"), "no collision line in the log");
    assert_eq!(true_speed(&app), 0.0);
}

/// Holds each key for its seconds in turn (auto-repeat at 30 Hz) from time `t`;
/// returns the time reached.
fn hold_in_turn(app: &mut App, plan: &[(char, f64)], mut t: f64) -> f64 {
    for &(c, seconds) in plan {
        let end = t + seconds;
        while t < end {
            app.handle_key(Key::char(c), KeyKind::Press, t);
            t += 1.0 / 30.0;
            app.update(t);
        }
    }
    t
}

/// Drives a fixed pattern in `mode` for about 15 s; returns the app afterwards.
fn drive_pattern(mut app: App, mode_key: char) -> App {
    app.handle_key(Key::char(mode_key), KeyKind::Press, 0.0);
    let mut t = 0.0;
    for _ in 0..6 {
        t = hold_in_turn(&mut app, &[('w', 1.5), ('a', 1.0)], t);
    }
    app
}

fn corrections(app: &App) -> u32 {
    app.pilot().slam().landmarks().map(|l| l.sightings).sum()
}

#[test]
fn race_mode_drives_faster_with_fewer_slam_corrections() {
    let manual = drive_pattern(default_app(), 'm');
    let race = drive_pattern(default_app(), 'r');
    assert_eq!(race.pilot().mode(), Mode::Race);
    assert!(race.pilot().teleop().linear_speed > manual.pilot().teleop().linear_speed);
    assert!(race.pilot().teleop().limits().0 > manual.pilot().teleop().limits().0);
    assert!(
        race.link().ground_truth().unwrap().distance_driven()
            > 1.5 * manual.link().ground_truth().unwrap().distance_driven()
    );
    let (m, r) = (corrections(&manual), corrections(&race));
    assert!(r * 2 < m, "race corrected {r} times, manual {m}");
    // Back to manual: manual's speeds and limits return.
    let mut race = race;
    race.handle_key(Key::char('m'), KeyKind::Press, race.now());
    assert_eq!(
        race.pilot().teleop().limits().0,
        manual.pilot().teleop().limits().0
    );
    assert_eq!(
        race.pilot().teleop().linear_speed,
        manual.pilot().teleop().linear_speed
    );
}

#[test]
fn race_mode_warns_when_the_pose_uncertainty_grows() {
    use navdeck::session::{LinkChoice, SessionSpec};
    let dir = std::env::temp_dir().join(format!("navdeck-race-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("race.toml");
    std::fs::write(
        &path,
        "[race]\ncorrect_every = 100000\nsigma_warning = 0.003\n",
    )
    .unwrap();
    let app = app_with(SessionSpec {
        world: None,
        seed: 1,
        start: None,
        config: Some(path),
        keymap: None,
        link: LinkChoice::Sim,
        localize: Default::default(),
    });
    let app = drive_pattern(app, 'r');
    assert!(
        app.log_book()
            .iter()
            .any(|e| e.text.starts_with("race: position uncertainty")),
        "no uncertainty warning: sigma {:?}, collisions {}",
        app.pilot().pose_sigma(),
        app.link().ground_truth().unwrap().collisions()
    );
}

/// A link whose every poll fails, like a serial device that was unplugged.
struct DeadLink;

impl navdeck::link::RobotLink for DeadLink {
    fn label(&self) -> String {
        "dead".into()
    }
    fn send(&mut self, _: &navdeck::link::Command) -> Result<(), navdeck::link::LinkError> {
        Ok(())
    }
    fn poll(&mut self, _: f64) -> Result<navdeck::link::SensorFrame, navdeck::link::LinkError> {
        Err(navdeck::link::LinkError::Lost("unplugged".into()))
    }
    fn stop(&mut self) {}
}

#[test]
fn drive_keys_on_a_lost_link_command_nothing_and_time_moves_on() {
    let mut app = App::new(
        navdeck::config::Config::default(),
        navdeck::keymap::Keymap::default_map(),
        Box::new(DeadLink),
        0.0,
    );
    app.update(0.1);
    app.handle_key(Key::char('w'), KeyKind::Press, 0.1);
    assert_eq!(app.pilot().commanded().linear, 0.0);
    app.update(2.0);
    assert_eq!(app.now(), 2.0);
    assert_eq!(app.pilot().commanded().linear, 0.0);
    assert!(app.held_keys().is_empty(), "the deadman let the key go");
}

/// The console on a link that answers while the returned flag says so.
fn flaky_app(up: bool) -> (App, std::sync::Arc<std::sync::atomic::AtomicBool>) {
    common::switched_app("flaky", "no odometry for 0.5 s", up)
}

#[test]
fn after_a_link_loss_the_robot_stays_still_until_a_key_is_pressed() {
    use navdeck::app::LinkStatus;
    use std::sync::atomic::Ordering;
    let (mut app, alive) = flaky_app(true);
    app.handle_key(Key::char('w'), KeyKind::Press, 0.1);
    app.update(0.2);
    assert!(
        app.pilot().commanded().linear > 0.0,
        "driving before the loss"
    );

    alive.store(false, Ordering::SeqCst);
    app.update(0.3);
    assert!(matches!(app.pilot().link_status(), LinkStatus::Lost(_)));
    assert_eq!(app.pilot().commanded().linear, 0.0);
    let screen = render(&app);
    assert!(screen.contains("LINK LOST"), "{screen}");

    // Data flows again: still no motion, and the first key only resumes control.
    alive.store(true, Ordering::SeqCst);
    app.update(0.5);
    assert_eq!(app.pilot().link_status(), &LinkStatus::Back);
    assert!(render(&app).contains("LINK BACK"));
    app.handle_key(Key::char('w'), KeyKind::Press, 0.6);
    app.update(0.7);
    assert_eq!(
        app.pilot().commanded().linear,
        0.0,
        "the resuming key does not drive"
    );
    assert_eq!(app.pilot().link_status(), &LinkStatus::Ok);
    assert!(app.log_book().iter().any(|e| e.text == "control resumed"));
    app.handle_key(Key::char('w'), KeyKind::Press, 0.8);
    app.update(0.9);
    assert!(
        app.pilot().commanded().linear > 0.0,
        "driving again after the resume"
    );
}

/// The log pane as a user reads it back: page back and forward, filter, search.
#[test]
fn the_log_pages_back_filters_by_level_and_searches() {
    let mut app = default_app();
    app.resize(100, 30);
    app.handle_key(key("e"), KeyKind::Press, 0.0);
    for k in 1..=600 {
        app.update(0.1 * f64::from(k));
    }
    app.handle_key(key("m"), KeyKind::Press, 60.05);
    let log_rows = |app: &navdeck::app::App| -> Vec<String> {
        let screen = common::render(app);
        let rows: Vec<String> = screen.lines().map(str::to_string).collect();
        let top = rows
            .iter()
            .position(|r| r.contains("┌ Log") || r.contains("┌ Log ·"));
        let top = top.unwrap_or_else(|| panic!("{screen}"));
        rows[top..].to_vec()
    };
    let newest = log_rows(&app);
    assert!(
        newest[0].contains("┌ Log ─"),
        "follows the newest: {}",
        newest[0]
    );
    app.handle_key(key("pageup"), KeyKind::Press, 60.1);
    let older = log_rows(&app);
    assert!(older[0].contains("newer below (PgDn)"), "{}", older[0]);
    assert_ne!(older[1..], newest[1..], "older lines shown");
    app.handle_key(key("pagedown"), KeyKind::Press, 60.2);
    assert_eq!(log_rows(&app)[1..], newest[1..], "back to the newest");
    // Warnings and worse only.
    app.handle_key(key("f"), KeyKind::Press, 60.3);
    let warnings = log_rows(&app);
    assert!(warnings[0].contains("warnings+"));
    for row in warnings[1..].iter().filter(|r| r.contains(':')) {
        assert!(row.contains("WARN") || row.contains("ERR"), "{row}");
    }
    app.handle_key(key("f"), KeyKind::Press, 60.4);
    app.handle_key(key("f"), KeyKind::Press, 60.5);
    // Lines containing a text, any case.
    app.handle_key(key("/"), KeyKind::Press, 60.6);
    for c in "found".chars() {
        app.handle_key(key(&c.to_string()), KeyKind::Press, 60.7);
    }
    app.handle_key(key("enter"), KeyKind::Press, 60.8);
    let found = log_rows(&app);
    assert!(found[0].contains("/found"), "{}", found[0]);
    let matching: Vec<_> = found[1..].iter().filter(|r| r.contains(':')).collect();
    assert!(!matching.is_empty());
    assert!(
        matching.iter().all(|r| r.to_lowercase().contains("found")),
        "{matching:?}"
    );
    // Routine lines of one shape are one line with a count.
    assert!(app.log_book().iter().any(|e| e.repeats > 1));
}

/// Esc and q leave the map picker for manual mode; neither quits the console.
#[test]
fn esc_and_q_leave_the_map_picker_without_quitting() {
    for leave in ["esc", "q"] {
        let mut app = default_app();
        app.handle_key(key("l"), KeyKind::Press, 0.0);
        assert_eq!(app.pilot().mode(), navdeck::app::mode::Mode::Load);
        app.handle_key(key(leave), KeyKind::Press, 0.1);
        assert_eq!(
            app.pilot().mode(),
            navdeck::app::mode::Mode::Manual,
            "{leave}"
        );
        assert!(!app.should_quit(), "{leave}");
    }
}

/// `:controller` alone names the controller instead of being an unknown command.
#[test]
fn a_bare_controller_command_names_the_controller() {
    let mut app = default_app();
    for c in ":controller".chars() {
        app.handle_key(key(&c.to_string()), KeyKind::Press, 0.0);
    }
    app.handle_key(key("enter"), KeyKind::Press, 0.1);
    let last = app.log_book().last().unwrap().text.clone();
    assert!(last.starts_with("path controller: Hybrid"), "{last}");
}

/// A fresh plan is never shown as "arrived", and a mission's path goes with a takeover.
#[test]
fn stale_path_state_goes_when_it_no_longer_applies() {
    let mut app = default_app();
    let typed = |app: &mut navdeck::app::App, text: &str, t: f64| {
        for c in text.chars() {
            app.handle_key(key(&c.to_string()), KeyKind::Press, t);
        }
        app.handle_key(key("enter"), KeyKind::Press, t);
    };
    typed(&mut app, ":goto 1.2 1.2", 0.5);
    app.handle_key(key("p"), KeyKind::Press, 0.6);
    let mut t = 0.6;
    while !app.pilot().arrived() && t < 60.0 {
        t += 0.1;
        app.update(t);
    }
    assert!(app.pilot().arrived(), "arrived by {t:.0} s");
    app.handle_key(key("t"), KeyKind::Press, t + 0.1);
    typed(&mut app, ":goto 0.9 1.2", t + 0.2);
    assert!(app.pilot().route().is_some());
    assert!(!app.pilot().arrived(), "a plan not yet driven");
    assert!(!common::render(&app).contains("arrived at"));
    // The mission's path does not outlive a takeover.
    app.handle_key(key("e"), KeyKind::Press, t + 0.3);
    for _ in 0..100 {
        t += 0.1;
        app.update(t + 0.3);
    }
    app.handle_key(key("w"), KeyKind::Press, t + 0.5);
    assert!(app.pilot().route().is_none());
}

/// The landmark table lists gates and blocks first, takes the arrows while open, and
/// enter plans to the chosen landmark as `:goto marker ID` does.
#[test]
fn the_landmark_table_chooses_a_gate_or_block_and_enter_plans_to_it() {
    let mut app = default_app();
    app.resize(120, 40);
    for k in 1..=30 {
        app.update(0.1 * f64::from(k));
    }
    app.handle_key(key("tab"), KeyKind::Press, 3.05);
    let all = app.listed_landmarks();
    assert!(all.len() > 5);
    let first_wall = all.iter().position(|l| l.id <= 300).unwrap();
    assert!(all[first_wall..].iter().all(|l| l.id <= 300), "walls last");
    app.handle_key(key("tab"), KeyKind::Press, 3.1);
    let targets = app.listed_landmarks();
    assert!(
        !targets.is_empty() && targets.iter().all(|l| l.id > 400),
        "gates & blocks only"
    );
    let screen = common::render(&app);
    assert!(screen.contains("Landmarks 1/"), "{screen}");
    let centre = app.view().center;
    app.handle_key(key("down"), KeyKind::Press, 3.2);
    assert_eq!(app.view().table.selected, 1.min(targets.len() - 1));
    assert_eq!(
        app.view().center,
        centre,
        "the arrow chose a row, it did not pan"
    );
    let chosen = targets[app.view().table.selected].id;
    app.handle_key(key("enter"), KeyKind::Press, 3.3);
    let route = app.pilot().route().expect("a plan to the chosen landmark");
    assert_eq!(route.label, format!("marker {chosen}"));
    app.handle_key(key("tab"), KeyKind::Press, 3.4);
    assert!(!app.view().landmarks, "a third tab closes it");
}

/// A link with no robot behind it: drive keys say why nothing moves, and the autonomous
/// modes refuse to start until the robot answers; the status shows the link's reason.
#[test]
fn with_the_link_down_keys_say_why_and_autonomy_waits_for_the_robot() {
    use navdeck::app::LinkStatus;
    let (mut app, alive) = flaky_app(false);
    app.update(0.2);
    assert!(matches!(app.pilot().link_status(), LinkStatus::Lost(_)));
    app.handle_key(Key::char('w'), KeyKind::Press, 0.3);
    let log: Vec<String> = app.log_book().iter().map(|e| e.text.clone()).collect();
    assert!(
        logged(&app, "forward: nothing moves while the link is lost"),
        "{log:?}"
    );
    app.handle_key(key("e"), KeyKind::Press, 0.4);
    assert_eq!(app.pilot().mode(), navdeck::app::mode::Mode::Manual);
    assert!(logged(
        &app,
        "exploration mode needs the robot to answer first"
    ));
    assert!(render(&app).contains("no odometry for"), "{}", render(&app));
    // Once the robot answers, the mission starts.
    alive.store(true, std::sync::atomic::Ordering::SeqCst);
    app.update(0.5);
    app.handle_key(key("e"), KeyKind::Press, 0.6);
    assert_eq!(app.pilot().mode(), navdeck::app::mode::Mode::Exploration);
}

/// `x` is the stop key in every mode: following a path, it stops the robot and hands it
/// to manual mode with the path kept; `p` follows it again.
#[test]
fn the_stop_key_stops_path_following_and_p_takes_it_up_again() {
    let mut app = default_app();
    for c in ":goto 1.2 1.2".chars() {
        app.handle_key(key(&c.to_string()), KeyKind::Press, 0.5);
    }
    app.handle_key(key("enter"), KeyKind::Press, 0.5);
    app.handle_key(key("p"), KeyKind::Press, 0.6);
    let mut t = 0.6;
    while app.pilot().commanded().linear < 0.05 && t < 10.0 {
        t += 0.1;
        app.update(t);
    }
    assert!(app.pilot().commanded().linear >= 0.05, "under way");
    app.handle_key(key("x"), KeyKind::Press, t + 0.05);
    app.update(t + 0.1);
    assert_eq!(app.pilot().mode(), Mode::Manual);
    assert_eq!(app.pilot().commanded().linear, 0.0, "stopped");
    assert!(app.pilot().route().is_some(), "the path is kept");
    let said = app.log_book().iter().any(|e| {
        e.text == "stop: path following paused, manual control (p follows the path again)"
    });
    assert!(said);
    app.handle_key(key("p"), KeyKind::Press, t + 0.2);
    assert_eq!(app.pilot().mode(), Mode::PathFollowing);
    // In manual mode x stops the keys held, as c does.
    app.handle_key(key("m"), KeyKind::Press, t + 0.3);
    app.handle_key(key("w"), KeyKind::Press, t + 0.4);
    app.handle_key(key("x"), KeyKind::Press, t + 0.45);
    app.update(t + 0.5);
    assert_eq!(app.pilot().commanded().linear, 0.0);
    assert!(app.held_keys().is_empty());
}

/// With no robot answering, the screen says why: the link's reason under the Link row,
/// and the keys' refusals in the log.
#[test]
fn link_down_screens_say_why() {
    let (mut app, _alive) = flaky_app(false);
    app.update(0.2);
    app.handle_key(Key::char('w'), KeyKind::Press, 0.3);
    app.handle_key(key("e"), KeyKind::Press, 0.4);
    app.update(0.5);
    for (w, h) in [(80, 24), (120, 40)] {
        app.resize(w, h);
        let screen = common::render_at(&app, w, h);
        assert!(screen.contains("forward: nothing moves"), "{screen}");
        insta::assert_snapshot!(format!("link_down_{w}x{h}"), screen);
    }
}
