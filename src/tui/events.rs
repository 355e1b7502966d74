//! Where the main loop's input and time come from: the wall clock (the terminal's input
//! is `tui::input`), or a script and a hand-turned clock in tests.

use crate::app::KeyKind;
use crate::keymap::Key;
use std::collections::VecDeque;
use std::io;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
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

pub use crate::clock::Clock;

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
pub struct ManualClock(Arc<AtomicU64>);

impl ManualClock {
    pub fn advance(&self, seconds: f64) {
        let now = f64::from_bits(self.0.load(Ordering::SeqCst));
        self.0.store((now + seconds).to_bits(), Ordering::SeqCst);
    }
}

impl Clock for ManualClock {
    fn now(&self) -> f64 {
        f64::from_bits(self.0.load(Ordering::SeqCst))
    }
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
