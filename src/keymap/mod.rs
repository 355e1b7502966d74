//! Keymaps as data: every binding lives in a file, none in code.
//!
//! The built-in bindings are `keymaps/default.toml`, compiled in. A user file is TOML with a
//! `[global]` section and one per mode (`[manual]`, `[exploration]`, `[thinking]`,
//! `[path_following]`, `[race]`, `[load]`) mapping key names to action names; each of its
//! bindings replaces the default for that key in that section, and `"none"` unbinds a key.
//! In a mode, the mode's section is consulted first, then `[global]`.
//!
//! Nothing here knows about terminals: the TUI turns its key events into [`Key`].

pub mod action;
mod error;
mod file;
mod key;
mod layers;
mod sequence;

pub use action::Action;
pub use error::KeymapError;
pub use key::{Key, KeyCode, KeyParseError};
pub use layers::Keymap;
pub use sequence::parse_key_sequence;
