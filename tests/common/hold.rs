//! A held key as scripted steps.

use super::press::press;
use navdeck::tui::events::Step;

/// Holds `c` for `seconds` as a terminal without release events does: a press, then
/// auto-repeats every 1/30 s.
pub fn hold(c: char, seconds: f64) -> Vec<Step> {
    let n = (seconds * 30.0).round() as usize;
    (0..n)
        .flat_map(|_| [press(c), Step::Wait(1.0 / 30.0)])
        .collect()
}
