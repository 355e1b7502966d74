//! A key press as a scripted step.

use navdeck::app::KeyKind;
use navdeck::keymap::Key;
use navdeck::tui::events::{Event, Step};

/// A key press step.
pub fn press(c: char) -> Step {
    Step::Event(Event::Key(Key::char(c), KeyKind::Press))
}
