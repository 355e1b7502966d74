//! Headless snapshots of the console's screen (insta over ratatui's TestBackend).

use crate::common;

use common::*;
use navdeck::tui::events::Step;

fn tab() -> Step {
    let key = navdeck::keymap::Key::new(navdeck::keymap::KeyCode::Tab);
    Step::Event(navdeck::tui::events::Event::Key(
        key,
        navdeck::app::KeyKind::Press,
    ))
}

fn snapshot_after(width: u16, height: u16, steps: Vec<Step>) -> String {
    screen(&run_script(default_app(), width, height, steps).terminal)
}

#[test]
fn start_screen_80x24() {
    insta::assert_snapshot!(snapshot_after(80, 24, vec![Step::Wait(0.5)]));
}

#[test]
fn start_screen_120x40() {
    insta::assert_snapshot!(snapshot_after(120, 40, vec![Step::Wait(0.5)]));
}

#[test]
fn manual_driving_after_keys_80x24() {
    let mut steps = hold('w', 2.0);
    steps.extend(hold('a', 0.5));
    steps.extend(hold('w', 1.0));
    insta::assert_snapshot!(snapshot_after(80, 24, steps));
}

#[test]
fn manual_driving_after_keys_120x40() {
    let mut steps = hold('a', 0.6);
    steps.extend(hold('w', 3.0));
    steps.push(Step::Wait(1.0));
    insta::assert_snapshot!(snapshot_after(120, 40, steps));
}

#[test]
fn help_overlay_80x24() {
    insta::assert_snapshot!(snapshot_after(80, 24, vec![press('?'), Step::Wait(0.1)]));
}

#[test]
fn help_overlay_120x40() {
    insta::assert_snapshot!(snapshot_after(120, 40, vec![press('?'), Step::Wait(0.1)]));
}

#[test]
fn narrow_terminal_60x24_stacks_the_status_under_the_map() {
    insta::assert_snapshot!(snapshot_after(60, 24, vec![Step::Wait(0.5)]));
}

#[test]
fn tiny_terminal_asks_for_more_room() {
    insta::assert_snapshot!(snapshot_after(30, 10, vec![Step::Wait(0.5)]));
}

#[test]
fn braille_map_zoomed_in_100x30() {
    let steps = vec![press('b'), press('+'), press('+'), Step::Wait(0.5)];
    insta::assert_snapshot!(snapshot_after(100, 30, steps));
}

#[test]
fn load_without_a_maps_folder_and_estop_in_the_log_80x24() {
    let mut steps = hold('w', 1.0);
    steps.extend([press('l'), press(' '), Step::Wait(0.5)]);
    insta::assert_snapshot!(snapshot_after(80, 24, steps));
}

#[test]
fn landmark_table_and_ellipses_after_a_drive_120x40() {
    let mut steps = hold('a', 0.8);
    steps.extend(hold('w', 2.0));
    steps.extend([tab(), press('+'), Step::Wait(0.3)]);
    insta::assert_snapshot!(snapshot_after(120, 40, steps));
}

#[test]
fn race_mode_80x24() {
    let mut steps = vec![press('r')];
    steps.extend(hold('w', 1.0));
    insta::assert_snapshot!(snapshot_after(80, 24, steps));
}

fn typed(text: &str) -> Vec<Step> {
    text.chars().map(press).collect()
}

fn enter() -> Step {
    Step::Event(navdeck::tui::events::Event::Key(
        "enter".parse().unwrap(),
        navdeck::app::KeyKind::Press,
    ))
}

#[test]
fn thinking_mode_with_a_planned_path_100x30() {
    let mut steps = vec![Step::Wait(1.0), press('t')];
    steps.extend(typed("llllllllllllllllllllkkkkkkkk"));
    steps.push(enter());
    steps.push(Step::Wait(0.2));
    insta::assert_snapshot!(snapshot_after(100, 30, steps));
}

#[test]
fn following_a_path_100x30() {
    let mut steps = typed(":goto 1.2 1.2");
    steps.push(enter());
    steps.extend([press('p'), Step::Wait(6.0)]);
    insta::assert_snapshot!(snapshot_after(100, 30, steps));
}

#[test]
fn exploration_mission_100x30() {
    let steps = vec![press('e'), Step::Wait(40.0)];
    insta::assert_snapshot!(snapshot_after(100, 30, steps));
}

fn key_step(name: &str) -> Step {
    Step::Event(navdeck::tui::events::Event::Key(
        name.parse().unwrap(),
        navdeck::app::KeyKind::Press,
    ))
}

/// The mission's log paged back once: older lines, and the title says how to come back.
#[test]
fn log_paged_back_during_the_mission_80x24() {
    let steps = vec![press('e'), Step::Wait(30.0), key_step("pageup")];
    insta::assert_snapshot!(snapshot_after(80, 24, steps));
}

/// Only warnings and worse, then only lines about the gripper.
#[test]
fn log_filtered_by_level_and_by_text_120x40() {
    // 75 s into the mission the log has warnings (a path blocked, an obstacle seen).
    let mut steps = vec![press('e'), Step::Wait(75.0), press('m'), press('f')];
    steps.push(Step::Wait(0.1));
    let mut by_text = vec![press('e'), Step::Wait(60.0), press('m'), press('/')];
    by_text.extend(typed("gripper"));
    by_text.push(enter());
    by_text.push(Step::Wait(0.1));
    let warnings = snapshot_after(120, 40, steps);
    let gripper = snapshot_after(120, 40, by_text);
    insta::assert_snapshot!(format!("{warnings}\n{gripper}"));
}

#[test]
fn a_40x12_terminal_is_too_small_and_says_what_it_needs() {
    let screen = snapshot_after(40, 12, vec![Step::Wait(0.5)]);
    assert!(
        screen.contains("terminal too small (need 60x16"),
        "{screen}"
    );
    insta::assert_snapshot!(screen);
}

/// At 200 x 60 the status panel is wide enough for the mission's state on one row.
#[test]
fn wide_terminal_grows_the_status_panel_200x60() {
    let steps = vec![press('e'), Step::Wait(30.0)];
    insta::assert_snapshot!(snapshot_after(200, 60, steps));
}

/// Gates and blocks only, the second row chosen: what `enter` would plan to.
#[test]
fn landmark_table_gates_and_blocks_80x24() {
    let mut steps = hold('a', 1.5);
    steps.extend([tab(), tab(), key_step("down"), Step::Wait(0.1)]);
    insta::assert_snapshot!(snapshot_after(80, 24, steps));
}

/// After a drive: the scan's hits (on by default), the trail (T) and, zoomed in until the
/// robot spans several columns, its footprint.
fn scan_trail_and_footprint_steps() -> Vec<Step> {
    let mut steps = hold('w', 2.0);
    steps.extend(hold('a', 0.6));
    steps.extend(hold('w', 1.0));
    steps.extend([press('T'), press('+'), press('+'), press('+'), press('+')]);
    steps.push(Step::Wait(0.2));
    steps
}

#[test]
fn scan_trail_and_footprint_zoomed_in_80x24() {
    let screen = snapshot_after(80, 24, scan_trail_and_footprint_steps());
    assert!(screen.contains('%') && screen.contains('·'), "{screen}");
    insta::assert_snapshot!(screen);
}

#[test]
fn scan_trail_and_footprint_zoomed_in_120x40() {
    let screen = snapshot_after(120, 40, scan_trail_and_footprint_steps());
    assert!(screen.contains('%') && screen.contains('·'), "{screen}");
    insta::assert_snapshot!(screen);
}

/// The stop key in exploration: the robot stops, the mission pauses, manual mode.
fn stop_during_exploration_steps() -> Vec<Step> {
    vec![press('e'), Step::Wait(20.0), press('x'), Step::Wait(1.0)]
}

#[test]
fn stop_key_pauses_exploration_80x24() {
    let screen = snapshot_after(80, 24, stop_during_exploration_steps());
    assert!(screen.contains("exploration paused"), "{screen}");
    insta::assert_snapshot!(screen);
}

#[test]
fn stop_key_pauses_exploration_120x40() {
    let screen = snapshot_after(120, 40, stop_during_exploration_steps());
    assert!(screen.contains("exploration paused"), "{screen}");
    insta::assert_snapshot!(screen);
}

/// `g` hides the twin's truth: no true pose on the map, no Truth and Error rows.
#[test]
fn truth_hidden_80x24() {
    let mut steps = hold('w', 1.0);
    steps.extend([press('g'), Step::Wait(0.2)]);
    let screen = snapshot_after(80, 24, steps);
    assert!(
        !screen.contains("Truth") && !screen.contains("Error"),
        "{screen}"
    );
    insta::assert_snapshot!(screen);
}

#[test]
fn truth_hidden_120x40() {
    let mut steps = hold('w', 1.0);
    steps.extend([press('g'), Step::Wait(0.2)]);
    let screen = snapshot_after(120, 40, steps);
    assert!(
        !screen.contains("Truth") && !screen.contains("Error"),
        "{screen}"
    );
    insta::assert_snapshot!(screen);
}

/// A log line longer than the pane wraps under its text instead of being cut.
fn long_line_steps() -> Vec<Step> {
    let mut steps = vec![Step::Wait(0.5), press(':')];
    steps.extend(typed("controller nonsense-that-is-not-a-controller"));
    steps.extend([enter(), Step::Wait(0.05)]);
    steps
}

#[test]
fn a_long_log_line_wraps_80x24() {
    insta::assert_snapshot!(snapshot_after(80, 24, long_line_steps()));
}

#[test]
fn a_long_log_line_wraps_120x40() {
    insta::assert_snapshot!(snapshot_after(120, 40, long_line_steps()));
}

/// The camera panel sits inside the map's border.
#[test]
fn camera_panel_inside_the_map_border_80x24() {
    let screen = snapshot_after(80, 24, vec![press('v'), Step::Wait(0.5)]);
    let second = screen.lines().nth(1).unwrap();
    assert!(second.starts_with("┌ Map"), "{second}");
    insta::assert_snapshot!(screen);
}

#[test]
fn log_paged_back_during_the_mission_120x40() {
    let steps = vec![press('e'), Step::Wait(30.0), key_step("pageup")];
    insta::assert_snapshot!(snapshot_after(120, 40, steps));
}

#[test]
fn log_filtered_by_level_80x24() {
    let steps = vec![
        press('e'),
        Step::Wait(75.0),
        press('m'),
        press('f'),
        Step::Wait(0.1),
    ];
    insta::assert_snapshot!(snapshot_after(80, 24, steps));
}

/// A plan not yet driven: the path and its goal, no "arrived".
fn planned_steps() -> Vec<Step> {
    let mut steps = vec![Step::Wait(1.0), press('t'), press(':')];
    steps.extend(typed("goto 1.2 1.2"));
    steps.extend([enter(), Step::Wait(0.2)]);
    steps
}

#[test]
fn a_fresh_plan_is_not_arrived_80x24() {
    let screen = snapshot_after(80, 24, planned_steps());
    assert!(!screen.contains("arrived"), "{screen}");
    insta::assert_snapshot!(screen);
}

#[test]
fn a_fresh_plan_is_not_arrived_120x40() {
    let screen = snapshot_after(120, 40, planned_steps());
    assert!(!screen.contains("arrived"), "{screen}");
    insta::assert_snapshot!(screen);
}
