//! A terminal that dies under the console, on the output side (writes fail with EIO) or
//! the input side (reads fail): the loop stops the robot and returns, it never spins.

use crate::common;

use common::{RecordingLink, hold, recording_app};
use navdeck::tui::events::{Event, EventSource, ManualClock, ScriptedEvents};
use navdeck::tui::run::RunError;
use ratatui::Terminal;
use ratatui::backend::{Backend, ClearType, TestBackend, WindowSize};
use ratatui::buffer::Cell;
use ratatui::layout::{Position, Size};
use std::io;
use std::time::Duration;

fn eio() -> io::Error {
    io::Error::from_raw_os_error(5)
}

/// A test terminal whose writes fail once `frames` frames have been drawn.
struct Dying {
    inner: TestBackend,
    frames: usize,
}

impl Backend for Dying {
    type Error = io::Error;

    fn draw<'a, I>(&mut self, content: I) -> io::Result<()>
    where
        I: Iterator<Item = (u16, u16, &'a Cell)>,
    {
        if self.frames == 0 {
            return Err(eio());
        }
        self.frames -= 1;
        self.inner.draw(content).map_err(|_| eio())
    }
    fn hide_cursor(&mut self) -> io::Result<()> {
        self.inner.hide_cursor().map_err(|_| eio())
    }
    fn show_cursor(&mut self) -> io::Result<()> {
        self.inner.show_cursor().map_err(|_| eio())
    }
    fn get_cursor_position(&mut self) -> io::Result<Position> {
        self.inner.get_cursor_position().map_err(|_| eio())
    }
    fn set_cursor_position<P: Into<Position>>(&mut self, position: P) -> io::Result<()> {
        self.inner.set_cursor_position(position).map_err(|_| eio())
    }
    fn clear(&mut self) -> io::Result<()> {
        self.inner.clear().map_err(|_| eio())
    }
    fn clear_region(&mut self, clear_type: ClearType) -> io::Result<()> {
        self.inner.clear_region(clear_type).map_err(|_| eio())
    }
    fn size(&self) -> io::Result<Size> {
        self.inner.size().map_err(|_| eio())
    }
    fn window_size(&mut self) -> io::Result<WindowSize> {
        self.inner.window_size().map_err(|_| eio())
    }
    fn flush(&mut self) -> io::Result<()> {
        if self.frames == 0 {
            return Err(eio());
        }
        self.inner.flush().map_err(|_| eio())
    }
}

/// Keys, then reads that fail as a hung-up terminal's do.
struct FailingInput(ScriptedEvents);

impl EventSource for FailingInput {
    fn next_event(&mut self, timeout: Duration) -> io::Result<Option<Event>> {
        match self.0.next_event(timeout)? {
            Some(Event::Closed) => Err(eio()),
            other => Ok(other),
        }
    }
}

fn stops(link: &RecordingLink) -> usize {
    *link.stops.lock().unwrap()
}

#[test]
fn a_write_to_a_dead_terminal_stops_the_robot_and_ends_the_loop() {
    let (mut app, link) = recording_app();
    let clock = ManualClock::default();
    // Keys that keep the screen changing, so frames keep being drawn until one fails.
    let mut events = ScriptedEvents::new(clock.clone(), hold('w', 5.0));
    let mut terminal = Terminal::new(Dying {
        inner: TestBackend::new(100, 30),
        frames: 3,
    })
    .unwrap();
    let (out, stats) = common::run_loop(&mut terminal, &mut app, &mut events, &clock);
    assert!(matches!(out, Err(RunError::Draw(_))), "{out:?}");
    assert!((1..=3).contains(&stats.frames_drawn), "{stats:?}");
    assert!(stops(&link) >= 1, "the robot was not told to stop");
    assert!(app.pilot().commanded().is_zero());
}

#[test]
fn a_read_error_from_the_terminal_stops_the_robot_and_ends_the_loop() {
    let (mut app, link) = recording_app();
    let clock = ManualClock::default();
    let mut events = FailingInput(ScriptedEvents::new(clock.clone(), hold('w', 1.0)));
    let mut terminal = Terminal::new(TestBackend::new(100, 30)).unwrap();
    let (out, _) = common::run_loop(&mut terminal, &mut app, &mut events, &clock);
    assert!(matches!(out, Err(RunError::Input(_))), "{out:?}");
    assert!(stops(&link) >= 1, "the robot was not told to stop");
    assert!(app.pilot().commanded().is_zero());
}
