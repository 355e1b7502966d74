//! Snapshots of the replay console (`navdeck replay`): paused half way through a recorded
//! exploration, as recorded and re-run, with the time bar along the bottom.

use crate::common;

use common::*;
use navdeck::replay::Replay;
use navdeck::replay::playback::{Playback, View};
use navdeck::tui::events::Step;
use navdeck::tui::run::Exit;
use std::sync::Arc;

/// A recorded exploration of the built-in arena (made once per test binary).
fn recording() -> std::path::PathBuf {
    static MADE: std::sync::OnceLock<std::path::PathBuf> = std::sync::OnceLock::new();
    MADE.get_or_init(|| {
        let dir =
            std::env::temp_dir().join(format!("navdeck-replay-screen-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("explore.mcap");
        let _ = std::fs::remove_file(&path);
        let mut app = default_app();
        navdeck::console::start_recording(&mut app, &path, Default::default(), true).unwrap();
        navdeck::runners::headless::run(&mut app, &[key("e")], 10.0);
        app.finish_recording().unwrap().unwrap();
        path
    })
    .clone()
}

/// Plays the recording in a `width` x `height` test terminal through `steps`.
fn play(view: View, width: u16, height: u16, steps: Vec<Step>) -> (String, Playback, Replay, Exit) {
    let recorded = Arc::new(navdeck::replay::load(&recording()).unwrap());
    let (screen, player, exit) = replay_played(recorded, view, false, (width, height), steps);
    (screen, player.playback, player.replay, exit)
}

/// Half way, then paused.
fn half_way_paused() -> Vec<Step> {
    vec![Step::Wait(0.5), press('5'), press(' '), Step::Wait(0.5)]
}

#[test]
fn paused_half_way_as_recorded_120x40() {
    let (text, playback, _, exit) = play(View::AsRecorded, 120, 40, half_way_paused());
    assert!(playback.paused);
    assert_eq!(exit, Exit::InputClosed);
    assert!(text.contains("as recorded"), "{text}");
    insta::assert_snapshot!(text);
}

#[test]
fn paused_half_way_re_run_120x40() {
    let mut steps = half_way_paused();
    steps.push(press('r'));
    steps.push(Step::Wait(0.2));
    let (text, playback, replay, _) = play(View::AsRecorded, 120, 40, steps);
    assert_eq!(playback.view, View::Rerun);
    // The re-run has caught up with the playback's time.
    assert!((replay.position() - playback.position()).abs() < 0.2);
    insta::assert_snapshot!(text);
}

#[test]
fn playing_at_fifty_times_covers_fifty_seconds_a_second() {
    let steps = vec![
        press(']'),
        press(']'),
        press(']'),
        press(']'),
        press(']'),
        Step::Wait(1.0),
    ];
    let (_, playback, replay, _) = play(View::AsRecorded, 200, 60, steps);
    assert_eq!(playback.speed, 50.0);
    let (start, _) = playback.span();
    assert!(
        (playback.position() - start - 50.0).abs() < 0.5,
        "{}",
        playback.position()
    );
    assert!(replay.position() > start + 49.0);
}

#[test]
fn q_leaves_and_a_typed_time_seeks() {
    let mut steps = vec![press(':')];
    steps.extend("1:30".chars().map(press));
    steps.push(Step::Event(navdeck::tui::events::Event::Key(
        key("enter"),
        navdeck::app::KeyKind::Press,
    )));
    steps.push(press(' '));
    steps.push(press('q'));
    let (text, playback, _, exit) = play(View::AsRecorded, 100, 30, steps);
    assert_eq!(exit, Exit::Quit);
    assert!((playback.position() - playback.span().0 - 90.0).abs() < 0.1);
    assert!(text.contains("01:30"), "{text}");
}
