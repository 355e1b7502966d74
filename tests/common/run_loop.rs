//! The console loop on any backend and event source.

use navdeck::app::App;
use navdeck::tui::events::{EventSource, ManualClock};
use navdeck::tui::run::{Exit, RunError, RunStats, run};
use navdeck::tui::theme::Theme;
use ratatui::Terminal;
use ratatui::backend::Backend;
use std::sync::atomic::AtomicUsize;

/// Runs the console loop on any backend and event source, with no signal and no colour.
pub fn run_loop<B: Backend>(
    terminal: &mut Terminal<B>,
    app: &mut App,
    events: &mut dyn EventSource,
    clock: &ManualClock,
) -> (Result<Exit, RunError>, RunStats) {
    let mut stats = RunStats::default();
    let out = run(
        terminal,
        app,
        events,
        clock,
        &AtomicUsize::new(0),
        Theme { color: false },
        &mut stats,
    );
    (out, stats)
}
