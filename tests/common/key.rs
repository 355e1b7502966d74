//! A key by its name in a keymap file.

use navdeck::keymap::Key;

/// The key `name` names ("enter", "up", "space", "w").
pub fn key(name: &str) -> Key {
    name.parse().expect("key name")
}
