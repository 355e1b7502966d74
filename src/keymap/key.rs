//! navdeck's own key type and the names keymap files and `--keys` give to keys.
//!
//! No terminal library appears here: the TUI converts its key events into [`Key`],
//! and the headless runner builds keys from names.

use std::fmt;
use std::str::FromStr;

/// One key press as navdeck sees it.
///
/// Shift is not a flag of its own: a shifted letter is its uppercase character and
/// shift-tab is [`KeyCode::BackTab`], so every chord has exactly one value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Key {
    pub code: KeyCode,
    pub ctrl: bool,
    pub alt: bool,
}

/// The key itself, without modifiers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum KeyCode {
    /// A printable character, case included (`'W'` is shift-w); `' '` is space.
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
    /// Function key: `F(1)` is f1.
    F(u8),
}

/// Why a key name (or a `--keys` sequence) was refused.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum KeyParseError {
    #[error("empty key name")]
    Empty,
    #[error("unknown key name \"{0}\" (expected one character, or one of {NAMED_KEYS_HELP})")]
    UnknownName(String),
    #[error(
        "\"{0}\": shift- goes only with a letter or tab; write the shifted character itself (\"?\", not \"shift-/\")"
    )]
    Shift(String),
    #[error("control character {0:?} is not a key name; write its name, e.g. \"tab\" or \"enter\"")]
    ControlChar(char),
    #[error("'<' at character {column} has no closing '>' (write \"<<\" for a literal '<')")]
    Unterminated { column: usize },
}

/// For error messages: the names [`FromStr`] knows besides single characters.
const NAMED_KEYS_HELP: &str = "space, enter, esc, tab, backtab, backspace, delete, insert, \
up, down, left, right, home, end, pageup, pagedown, f1, f2, …, lt (<), gt (>), \
each optionally after ctrl-, alt- or shift-";

/// Named keys, canonical name first; later entries for the same code are accepted aliases.
const NAMES: [(&str, KeyCode); 24] = [
    ("space", KeyCode::Char(' ')),
    ("lt", KeyCode::Char('<')),
    ("gt", KeyCode::Char('>')),
    ("enter", KeyCode::Enter),
    ("return", KeyCode::Enter),
    ("esc", KeyCode::Esc),
    ("escape", KeyCode::Esc),
    ("tab", KeyCode::Tab),
    ("backtab", KeyCode::BackTab),
    ("backspace", KeyCode::Backspace),
    ("delete", KeyCode::Delete),
    ("del", KeyCode::Delete),
    ("insert", KeyCode::Insert),
    ("ins", KeyCode::Insert),
    ("up", KeyCode::Up),
    ("down", KeyCode::Down),
    ("left", KeyCode::Left),
    ("right", KeyCode::Right),
    ("home", KeyCode::Home),
    ("end", KeyCode::End),
    ("pageup", KeyCode::PageUp),
    ("pgup", KeyCode::PageUp),
    ("pagedown", KeyCode::PageDown),
    ("pgdn", KeyCode::PageDown),
];

impl Key {
    /// A character key with no modifiers; pass `'W'` for shift-w.
    pub fn char(c: char) -> Key {
        Key::new(KeyCode::Char(c))
    }

    /// A key with no modifiers.
    pub fn new(code: KeyCode) -> Key {
        Key {
            code,
            ctrl: false,
            alt: false,
        }
    }
}

impl FromStr for Key {
    type Err = KeyParseError;

    /// Reads `w`, `W`, `shift-w`, `space`, `ctrl-c`, `C-c`, `alt-x`, `up`, `f1`, `?`, `ctrl--` ….
    /// Modifier and key names ignore case; a single character keeps its case.
    fn from_str(s: &str) -> Result<Key, KeyParseError> {
        if s.is_empty() {
            return Err(KeyParseError::Empty);
        }
        let (mut ctrl, mut alt, mut shift) = (false, false, false);
        let mut rest = s;
        while let Some((prefix, tail)) = rest.split_once('-') {
            if tail.is_empty() {
                break;
            }
            match prefix.to_ascii_lowercase().as_str() {
                "ctrl" | "control" | "c" => ctrl = true,
                "alt" | "meta" | "a" | "m" => alt = true,
                "shift" | "s" => shift = true,
                _ => break,
            }
            rest = tail;
        }
        let mut code = code_from_name(rest, s)?;
        if shift {
            code = shifted(code).ok_or_else(|| KeyParseError::Shift(s.to_string()))?;
        }
        Ok(Key { code, ctrl, alt })
    }
}

/// The code a name (without modifiers) stands for; `whole` is the full name for errors.
fn code_from_name(name: &str, whole: &str) -> Result<KeyCode, KeyParseError> {
    let mut chars = name.chars();
    if let (Some(c), None) = (chars.next(), chars.next()) {
        if c.is_control() {
            return Err(KeyParseError::ControlChar(c));
        }
        return Ok(KeyCode::Char(c));
    }
    let lower = name.to_ascii_lowercase();
    if let Some((_, code)) = NAMES.iter().find(|(n, _)| *n == lower) {
        return Ok(*code);
    }
    let number = lower
        .strip_prefix('f')
        .filter(|digits| !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()))
        .and_then(|digits| digits.parse::<u8>().ok());
    if let Some(n @ 1..) = number {
        return Ok(KeyCode::F(n));
    }
    Err(KeyParseError::UnknownName(whole.to_string()))
}

/// What shift does to a code: letters go uppercase, tab becomes backtab, nothing else has a meaning.
fn shifted(code: KeyCode) -> Option<KeyCode> {
    match code {
        KeyCode::Char(c) if c.is_alphabetic() => {
            let mut upper = c.to_uppercase();
            match (upper.next(), upper.next()) {
                (Some(u), None) => Some(KeyCode::Char(u)),
                _ => None,
            }
        }
        KeyCode::Tab | KeyCode::BackTab => Some(KeyCode::BackTab),
        _ => None,
    }
}

impl fmt::Display for KeyCode {
    /// The canonical name: the character itself, or the first name in [`NAMES`], or `f<n>`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            KeyCode::Char(' ') => f.write_str("space"),
            KeyCode::Char(c) => write!(f, "{c}"),
            KeyCode::F(n) => write!(f, "f{n}"),
            named => {
                let name = NAMES
                    .iter()
                    .find(|(_, code)| code == named)
                    .map_or("?", |(name, _)| name);
                f.write_str(name)
            }
        }
    }
}

impl fmt::Display for Key {
    /// `ctrl-` then `alt-` then the code's name: "ctrl-c", "alt-x", "W", "space", "f1".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.ctrl {
            f.write_str("ctrl-")?;
        }
        if self.alt {
            f.write_str("alt-")?;
        }
        write!(f, "{}", self.code)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(s: &str) -> Key {
        s.parse().unwrap_or_else(|e| panic!("{s:?}: {e}"))
    }

    #[test]
    fn every_code_round_trips_through_its_name() {
        let codes = [
            KeyCode::Char('w'),
            KeyCode::Char('W'),
            KeyCode::Char(' '),
            KeyCode::Char('-'),
            KeyCode::Char('<'),
            KeyCode::Char('?'),
            KeyCode::Char('é'),
            KeyCode::Enter,
            KeyCode::Esc,
            KeyCode::Tab,
            KeyCode::BackTab,
            KeyCode::Backspace,
            KeyCode::Delete,
            KeyCode::Insert,
            KeyCode::Up,
            KeyCode::Down,
            KeyCode::Left,
            KeyCode::Right,
            KeyCode::Home,
            KeyCode::End,
            KeyCode::PageUp,
            KeyCode::PageDown,
            KeyCode::F(1),
            KeyCode::F(12),
            KeyCode::F(35),
        ];
        for code in codes {
            for (ctrl, alt) in [(false, false), (true, false), (false, true), (true, true)] {
                let k = Key { code, ctrl, alt };
                let name = k.to_string();
                assert_eq!(name.parse::<Key>(), Ok(k), "{name:?}");
            }
        }
    }

    #[test]
    fn canonical_names_are_the_short_readable_ones() {
        assert_eq!(Key::char(' ').to_string(), "space");
        assert_eq!(key("C-c").to_string(), "ctrl-c");
        assert_eq!(key("Escape").to_string(), "esc");
        assert_eq!(key("PgDn").to_string(), "pagedown");
        assert_eq!(key("shift-tab").to_string(), "backtab");
        assert_eq!(key("F7").to_string(), "f7");
    }

    #[test]
    fn shift_of_a_letter_is_the_uppercase_letter() {
        assert_eq!(key("shift-w"), Key::char('W'));
        assert_eq!(key("S-w"), key("W"));
        assert_ne!(key("W"), key("w"));
        assert_eq!(key("ctrl-shift-x"), key("ctrl-X"));
        assert!(matches!(
            "shift-1".parse::<Key>(),
            Err(KeyParseError::Shift(_))
        ));
        assert!(matches!(
            "shift-up".parse::<Key>(),
            Err(KeyParseError::Shift(_))
        ));
    }

    #[test]
    fn named_keys_ignore_case_but_characters_keep_it() {
        assert_eq!(key("SPACE"), Key::char(' '));
        assert_eq!(key("Up"), Key::new(KeyCode::Up));
        assert_eq!(key("CTRL-c"), key("ctrl-c"));
        assert_ne!(key("ctrl-C"), key("ctrl-c"));
    }

    #[test]
    fn dashes_are_keys_too() {
        assert_eq!(key("-"), Key::char('-'));
        let ctrl_minus = key("ctrl--");
        assert!(ctrl_minus.ctrl);
        assert_eq!(ctrl_minus.code, KeyCode::Char('-'));
    }

    #[test]
    fn nonsense_is_refused_not_guessed() {
        for bad in [
            "", "bogus", "ww", "ctrl-", "f0", "f256", "f+1", "hyper-x", "--", "\t",
        ] {
            assert!(bad.parse::<Key>().is_err(), "{bad:?} was accepted");
        }
        let err = "flap".parse::<Key>().unwrap_err().to_string();
        assert!(err.contains("\"flap\"") && err.contains("pageup"), "{err}");
    }
}
