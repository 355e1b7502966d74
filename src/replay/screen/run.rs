//! The replay's loop: the playback clock moves with the wall clock at the chosen
//! speed; the re-run follows it; a frame is drawn at most `FPS` times a second while
//! playing, and when something changed while paused.

use super::played::Played;
use super::{BAR_ROWS, draw};
use crate::replay::Replay;
use crate::replay::playback::{Asked, Playback};
use crate::tui::events::{Clock, Event, EventSource};
use crate::tui::run::{Exit, RunError, RunStats};
use crate::tui::theme::Theme;
use ratatui::Terminal;
use ratatui::backend::Backend;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

/// Frames a second while playing.
pub const FPS: f64 = 30.0;
/// The loop wakes at least this often while paused, so signals are seen promptly.
const MAX_WAIT: f64 = 0.1;

/// A recording being played: the re-run and the playback's clock and controls.
pub struct Player<R: Played = Replay> {
    pub replay: R,
    pub playback: Playback,
}

/// Plays `player`'s recording until quit, a signal or closed input.
pub fn run<B: Backend, R: Played>(
    terminal: &mut Terminal<B>,
    player: &mut Player<R>,
    events: &mut dyn EventSource,
    clock: &dyn Clock,
    signal: &AtomicUsize,
    theme: Theme,
    stats: &mut RunStats,
) -> Result<Exit, RunError> {
    let Player { replay, playback } = player;
    let size = terminal.size().map_err(|e| RunError::Draw(e.to_string()))?;
    replay.show_on_screen(size.width, size.height.saturating_sub(BAR_ROWS));
    let mut last = clock.now();
    let mut dirty = true;
    loop {
        let pending = signal.load(Ordering::SeqCst);
        if pending != 0 {
            return Ok(Exit::Signal(pending));
        }
        let now = clock.now();
        let before = playback.position();
        playback.advance(now - last);
        last = now;
        replay.run_to(playback.position());
        dirty |= playback.position() != before;
        if dirty {
            terminal
                .draw(|frame| draw(frame, replay, playback, theme))
                .map_err(|e| RunError::Draw(e.to_string()))?;
            stats.frames_drawn += 1;
            dirty = false;
        }
        let wait = if playback.paused { MAX_WAIT } else { 1.0 / FPS };
        match events.next_event(Duration::from_secs_f64(wait))? {
            None => {}
            Some(Event::Closed) => return Ok(Exit::InputClosed),
            Some(Event::Resize(w, h)) => {
                replay.show_on_screen(w, h.saturating_sub(BAR_ROWS));
                dirty = true;
            }
            Some(Event::Key(key, kind)) => {
                stats.events += 1;
                if kind == crate::app::KeyKind::Release {
                    continue;
                }
                dirty = true;
                match playback.key(key) {
                    Asked::Quit => return Ok(Exit::Quit),
                    Asked::Nothing => {}
                    Asked::Seek(t) => {
                        if let Err(e) = replay.seek(t) {
                            playback.refusal = Some(format!("cannot seek: {e}"));
                        }
                    }
                    Asked::View(key) => view_key(replay, key),
                }
            }
        }
    }
}

/// Keys that change only how the map is shown go to the re-run's console (zoom, pan,
/// braille, truth, scan, trail, log filter); anything that would steer it is refused.
fn view_key(replay: &mut impl Played, key: crate::keymap::Key) {
    use crate::keymap::Action;
    let action = (replay.app().keymap()).lookup(crate::pilot::mode::Mode::Manual, key);
    // A fleet's replay shows another robot; the recording's selection stays.
    match action {
        Some(Action::NextRobot) => return replay.show_next(1),
        Some(Action::PreviousRobot) => return replay.show_next(-1),
        _ => {}
    }
    let app = replay.app_mut();
    let shown = matches!(
        action,
        Some(
            Action::ZoomIn
                | Action::ZoomOut
                | Action::PanLeft
                | Action::PanRight
                | Action::PanUp
                | Action::PanDown
                | Action::CenterView
                | Action::ToggleBraille
                | Action::ToggleTruth
                | Action::ToggleScan
                | Action::ToggleTrail
                | Action::LogFilter
                | Action::LogSource
        )
    );
    if let (true, Some(action)) = (shown, action) {
        app.apply(action);
    }
}
