//! Scripted console sessions: the real loop on a test terminal, fed scripted steps on a
//! manual clock.

use navdeck::app::App;
use navdeck::tui::events::{ManualClock, ScriptedEvents, Step};
use navdeck::tui::run::{Exit, RunStats, run};
use navdeck::tui::theme::Theme;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use std::sync::atomic::AtomicUsize;

/// A scripted session's outcome.
// Each test reads the parts it checks; some read only the terminal.
#[allow(dead_code)]
pub struct Scripted {
    pub terminal: Terminal<TestBackend>,
    pub app: App,
    pub exit: Exit,
    pub stats: RunStats,
}

/// Runs `app` in a `width` x `height` test terminal through `steps`, without colour.
pub fn run_script(app: App, width: u16, height: u16, steps: Vec<Step>) -> Scripted {
    run_script_with_signal(app, width, height, steps, &AtomicUsize::new(0))
}

/// `run_script` with the signal flag the loop watches.
pub fn run_script_with_signal(
    mut app: App,
    width: u16,
    height: u16,
    steps: Vec<Step>,
    signal: &AtomicUsize,
) -> Scripted {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    let clock = ManualClock::default();
    let mut events = ScriptedEvents::new(clock.clone(), steps);
    let mut stats = RunStats::default();
    let exit = run(
        &mut terminal,
        &mut app,
        &mut events,
        &clock,
        signal,
        Theme { color: false },
        &mut stats,
    )
    .expect("the loop runs");
    Scripted {
        terminal,
        app,
        exit,
        stats,
    }
}
