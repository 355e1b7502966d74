//! A recording played in the replay console on a test terminal, as `navdeck replay`
//! plays it, through scripted keys on a manual clock.

use navdeck::record::recorded::Recorded;
use navdeck::replay::playback::{Playback, View};
use navdeck::replay::screen::run::Player;
use navdeck::replay::{Replay, ReplayOptions};
use navdeck::tui::events::{ManualClock, ScriptedEvents, Step};
use navdeck::tui::run::{Exit, RunStats};
use navdeck::tui::theme::Theme;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use std::sync::Arc;
use std::sync::atomic::AtomicUsize;

/// Plays `recorded` from its start in `view` (paused there when `paused`) in a
/// `width` x `height` terminal through `steps`: the last screen, the player, the exit.
pub fn replay_played(
    recorded: Arc<Recorded>,
    view: View,
    paused: bool,
    (width, height): (u16, u16),
    steps: Vec<Step>,
) -> (String, Player, Exit) {
    let replay = Replay::new(recorded, ReplayOptions::default()).unwrap();
    let mut playback = Playback::new(replay.span(), 1.0, view, 0.1);
    playback.paused = paused;
    let mut player = Player { replay, playback };
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    let clock = ManualClock::default();
    let mut events = ScriptedEvents::new(clock.clone(), steps);
    let exit = navdeck::replay::screen::run::run(
        &mut terminal,
        &mut player,
        &mut events,
        &clock,
        &AtomicUsize::new(0),
        Theme { color: false },
        &mut RunStats::default(),
    )
    .unwrap();
    (super::screen::screen(&terminal), player, exit)
}
