//! The main loop: events in, actions to the app, frames out when something changed.
//! It takes its backend, event source and clock as parameters, so tests drive it
//! with a script and a `TestBackend`.

use super::deck::Deck;
use super::events::{Clock, Event, EventSource};
use super::signals::signal_name;
use super::theme::Theme;
use ratatui::Terminal;
use ratatui::backend::Backend;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

/// The loop wakes at least this often, so signals are seen promptly.
const MAX_WAIT: f64 = 0.1;

/// Why the loop ended. In every case the robot has been told to stop.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Exit {
    Quit,
    /// A signal arrived (SIGINT, SIGTERM, SIGHUP on an SSH drop): its number.
    Signal(usize),
    /// The input ended.
    InputClosed,
}

#[derive(Debug, thiserror::Error)]
pub enum RunError {
    #[error("cannot draw to the terminal: {0}")]
    Draw(String),
    #[error("cannot read the terminal: {0}")]
    Input(#[from] std::io::Error),
}

/// What the loop did, for tests and the exit message.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct RunStats {
    pub frames_drawn: u64,
    pub events: u64,
}

/// Runs the console until quit, a signal, closed input or a terminal error.
/// `signal` holds the number of a pending signal, 0 for none.
pub fn run<B: Backend, D: Deck + ?Sized>(
    terminal: &mut Terminal<B>,
    app: &mut D,
    events: &mut dyn EventSource,
    clock: &dyn Clock,
    signal: &AtomicUsize,
    theme: Theme,
    stats: &mut RunStats,
) -> Result<Exit, RunError> {
    let size = terminal.size().map_err(|e| fail(app, e))?;
    app.resize(size.width, size.height);
    let mut drawn: Option<u64> = None;
    loop {
        if let Some(exit) = signalled(app, signal) {
            return Ok(exit);
        }
        app.update(clock.now());
        if app.should_quit() {
            return Ok(Exit::Quit);
        }
        if drawn != Some(app.revision()) {
            terminal
                .draw(|frame| app.draw(frame, theme))
                .map_err(|e| fail(app, e))?;
            drawn = Some(app.revision());
            stats.frames_drawn += 1;
        }
        let wait = (app.next_deadline() - clock.now()).clamp(0.0, MAX_WAIT);
        match events.next_event(Duration::from_secs_f64(wait)) {
            Ok(Some(event)) => {
                stats.events += 1;
                match event {
                    Event::Key(key, kind) => app.handle_key(key, kind, clock.now()),
                    Event::Resize(w, h) => app.resize(w, h),
                    Event::Closed => {
                        // A hang-up also sends SIGHUP, which may have arrived first.
                        if let Some(exit) = signalled(app, signal) {
                            return Ok(exit);
                        }
                        app.shutdown("input closed");
                        return Ok(Exit::InputClosed);
                    }
                }
            }
            Ok(None) => {}
            Err(e) => {
                if let Some(exit) = signalled(app, signal) {
                    return Ok(exit);
                }
                // A terminal that errors (EIO after a hang-up) has gone: stop and leave.
                app.shutdown(&format!("terminal input failed: {e}"));
                return Err(RunError::Input(e));
            }
        }
    }
}

/// Stops the robot and names the signal, if one has arrived.
fn signalled<D: Deck + ?Sized>(app: &mut D, signal: &AtomicUsize) -> Option<Exit> {
    let pending = signal.load(Ordering::SeqCst);
    if pending == 0 {
        return None;
    }
    app.shutdown(&format!("signal {}", signal_name(pending)));
    Some(Exit::Signal(pending))
}

fn fail<D: Deck + ?Sized>(app: &mut D, e: impl std::fmt::Display) -> RunError {
    let message = e.to_string();
    app.shutdown(&format!("terminal output failed: {message}"));
    RunError::Draw(message)
}
