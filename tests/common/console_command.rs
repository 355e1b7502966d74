//! Typing a console command, and running the console on, at session time.

use super::key::key;
use navdeck::app::{App, KeyKind};
use navdeck::keymap::Key;

/// Types `line` after `:` and presses Enter, at the console's time.
pub fn command(app: &mut App, line: &str) {
    let t = app.now();
    app.handle_key(Key::char(':'), KeyKind::Press, t);
    for c in line.chars() {
        app.handle_key(Key::char(c), KeyKind::Press, t);
    }
    app.handle_key(key("enter"), KeyKind::Press, t);
}

/// Runs the console on until session time `until`, a control period at a time.
pub fn run_to(app: &mut App, until: f64) {
    let mut t = app.now();
    while t < until - 1e-9 {
        t = (t + 0.1).min(until);
        app.update(t);
    }
}
