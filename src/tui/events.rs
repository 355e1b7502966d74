//! Where the main loop's input and time come from: the real terminal and clock, or a
//! script and a hand-turned clock in tests.

use crate::app::KeyKind;
use crate::keymap::{Key, KeyCode};
use crossterm::event::{self, KeyEventKind, KeyModifiers};
use std::cell::Cell;
use std::collections::VecDeque;
use std::io;
use std::rc::Rc;
use std::time::{Duration, Instant};

/// One input the console reacts to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Event {
    Key(Key, KeyKind),
    Resize(u16, u16),
    /// Input ended (stdin closed, script finished): stop the robot and leave.
    Closed,
}

/// Blocks for at most `timeout` waiting for the next input.
pub trait EventSource {
    fn next_event(&mut self, timeout: Duration) -> io::Result<Option<Event>>;
}

/// The session clock in seconds.
pub trait Clock {
    fn now(&self) -> f64;
}

/// Wall time since the console started.
pub struct WallClock(Instant);

impl WallClock {
    pub fn start() -> Self {
        Self(Instant::now())
    }
}

impl Clock for WallClock {
    fn now(&self) -> f64 {
        self.0.elapsed().as_secs_f64()
    }
}

/// A clock that moves only when told: shared between a script and the loop.
#[derive(Clone, Default)]
pub struct ManualClock(Rc<Cell<f64>>);

impl ManualClock {
    pub fn advance(&self, seconds: f64) {
        self.0.set(self.0.get() + seconds);
    }
}

impl Clock for ManualClock {
    fn now(&self) -> f64 {
        self.0.get()
    }
}

/// Terminal input through crossterm.
pub struct TerminalEvents;

impl EventSource for TerminalEvents {
    fn next_event(&mut self, timeout: Duration) -> io::Result<Option<Event>> {
        if !event::poll(timeout)? {
            return Ok(None);
        }
        Ok(match event::read()? {
            event::Event::Key(k) => key_from_crossterm(k).map(|(key, kind)| Event::Key(key, kind)),
            event::Event::Resize(w, h) => Some(Event::Resize(w, h)),
            _ => None,
        })
    }
}

/// crossterm's key event as navdeck's key; `None` for keys navdeck has no name for.
pub fn key_from_crossterm(k: event::KeyEvent) -> Option<(Key, KeyKind)> {
    use event::KeyCode as C;
    let code = match k.code {
        C::Char(c) => KeyCode::Char(c),
        C::Enter => KeyCode::Enter,
        C::Esc => KeyCode::Esc,
        C::Tab => KeyCode::Tab,
        C::BackTab => KeyCode::BackTab,
        C::Backspace => KeyCode::Backspace,
        C::Delete => KeyCode::Delete,
        C::Insert => KeyCode::Insert,
        C::Up => KeyCode::Up,
        C::Down => KeyCode::Down,
        C::Left => KeyCode::Left,
        C::Right => KeyCode::Right,
        C::Home => KeyCode::Home,
        C::End => KeyCode::End,
        C::PageUp => KeyCode::PageUp,
        C::PageDown => KeyCode::PageDown,
        C::F(n) => KeyCode::F(n),
        _ => return None,
    };
    let kind = match k.kind {
        KeyEventKind::Press => KeyKind::Press,
        KeyEventKind::Repeat => KeyKind::Repeat,
        KeyEventKind::Release => KeyKind::Release,
    };
    let key = Key {
        code,
        ctrl: k.modifiers.contains(KeyModifiers::CONTROL),
        alt: k.modifiers.contains(KeyModifiers::ALT),
    };
    Some((key, kind))
}

/// A step of a scripted session.
#[derive(Clone, Debug, PartialEq)]
pub enum Step {
    Event(Event),
    /// Let this many seconds pass with no input.
    Wait(f64),
}

/// Plays steps in order, turning a `ManualClock` for the waits; then reports `Closed`.
pub struct ScriptedEvents {
    steps: VecDeque<Step>,
    clock: ManualClock,
}

impl ScriptedEvents {
    pub fn new(clock: ManualClock, steps: impl IntoIterator<Item = Step>) -> Self {
        Self {
            steps: steps.into_iter().collect(),
            clock,
        }
    }

    /// Presses each key once, `gap` seconds apart.
    pub fn keys(keys: &[Key], gap: f64) -> Vec<Step> {
        keys.iter()
            .flat_map(|&k| [Step::Event(Event::Key(k, KeyKind::Press)), Step::Wait(gap)])
            .collect()
    }
}

impl EventSource for ScriptedEvents {
    fn next_event(&mut self, timeout: Duration) -> io::Result<Option<Event>> {
        match self.steps.front_mut() {
            None => Ok(Some(Event::Closed)),
            Some(Step::Event(_)) => match self.steps.pop_front() {
                Some(Step::Event(e)) => Ok(Some(e)),
                _ => unreachable!("front was an event"),
            },
            Some(Step::Wait(left)) => {
                // Time always passes, as it does for a real terminal: at least 1 ms a call.
                let dt = timeout.as_secs_f64().max(1e-3).min(*left);
                self.clock.advance(dt);
                *left -= dt;
                if *left <= 1e-12 {
                    self.steps.pop_front();
                }
                Ok(None)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shifted_letter_and_ctrl_c_convert() {
        let w = event::KeyEvent::new(C::Char('W'), KeyModifiers::SHIFT);
        assert_eq!(
            key_from_crossterm(w),
            Some((Key::char('W'), KeyKind::Press))
        );
        let c = event::KeyEvent::new(C::Char('c'), KeyModifiers::CONTROL);
        let (key, _) = key_from_crossterm(c).unwrap();
        assert!(key.ctrl && key.code == KeyCode::Char('c'));
    }
    use event::KeyCode as C;

    #[test]
    fn script_waits_turn_the_clock() {
        let clock = ManualClock::default();
        let mut s = ScriptedEvents::new(clock.clone(), [Step::Wait(0.25)]);
        assert_eq!(s.next_event(Duration::from_millis(100)).unwrap(), None);
        assert_eq!(s.next_event(Duration::from_millis(100)).unwrap(), None);
        assert_eq!(s.next_event(Duration::from_millis(100)).unwrap(), None);
        assert!((clock.now() - 0.25).abs() < 1e-12);
        assert_eq!(s.next_event(Duration::ZERO).unwrap(), Some(Event::Closed));
    }
}
