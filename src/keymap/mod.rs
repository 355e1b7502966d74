//! Keymaps as data (stand-in until the keymap module lands; same API).

use crate::app::action::Action;
use crate::app::mode::Mode;
use std::path::Path;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum KeyCode {
    Char(char),
    Enter,
    Esc,
    Tab,
    BackTab,
    Backspace,
    Delete,
    Insert,
    Up,
    Down,
    Left,
    Right,
    Home,
    End,
    PageUp,
    PageDown,
    F(u8),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Key {
    pub code: KeyCode,
    pub ctrl: bool,
    pub alt: bool,
}

impl Key {
    pub fn char(c: char) -> Key {
        Key::new(KeyCode::Char(c))
    }
    pub fn new(code: KeyCode) -> Key {
        Key {
            code,
            ctrl: false,
            alt: false,
        }
    }
}

impl std::fmt::Display for Key {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.code {
            KeyCode::Char(' ') => write!(f, "space"),
            KeyCode::Char(c) => write!(f, "{c}"),
            other => write!(f, "{other:?}"),
        }
    }
}

#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct KeyParseError(String);

#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct KeymapError(String);

pub fn parse_key_sequence(s: &str) -> Result<Vec<Key>, KeyParseError> {
    Ok(s.chars().map(Key::char).collect())
}

#[derive(Clone, Debug)]
pub struct Keymap {}

impl Keymap {
    pub fn default_map() -> Keymap {
        Keymap {}
    }
    pub fn load(_path: &Path) -> Result<Keymap, KeymapError> {
        Ok(Keymap {})
    }
    pub fn lookup(&self, mode: Mode, key: Key) -> Option<Action> {
        let KeyCode::Char(c) = key.code else {
            return None;
        };
        let manual = mode == Mode::Manual;
        Some(match c {
            'w' if manual => Action::Forward,
            's' if manual => Action::Backward,
            'a' if manual => Action::TurnLeft,
            'd' if manual => Action::TurnRight,
            'c' if manual => Action::Stop,
            'c' => Action::GripperClose,
            'o' => Action::GripperOpen,
            'm' => Action::ModeManual,
            'e' => Action::ModeExplore,
            'q' => Action::Quit,
            '?' => Action::Help,
            ' ' => Action::EmergencyStop,
            _ => return None,
        })
    }
    pub fn bindings(&self, mode: Mode) -> Vec<(Action, Vec<Key>)> {
        "wsadcomeq? "
            .chars()
            .filter_map(|c| {
                self.lookup(mode, Key::char(c))
                    .map(|a| (a, vec![Key::char(c)]))
            })
            .collect()
    }
    pub fn source(&self) -> &str {
        "built-in"
    }
}
