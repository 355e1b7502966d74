//! Why a keymap file was refused: always the file and line, and the offending text.

use super::key::KeyParseError;
use std::path::PathBuf;

/// A keymap that cannot be used. Shown before the terminal enters raw mode.
#[derive(Debug, thiserror::Error)]
pub enum KeymapError {
    #[error("cannot read keymap {}: {error}", path.display())]
    Read {
        path: PathBuf,
        error: std::io::Error,
    },
    /// The file is not valid TOML (this includes a key written twice in one table).
    #[error("{}:{line}: {message}", path.display())]
    Toml {
        path: PathBuf,
        line: usize,
        message: String,
    },
    #[error(
        "{}:{line}: unknown section [{section}] (expected [global], [manual], [exploration], [thinking], [path_following], [race] or [load])",
        path.display()
    )]
    UnknownSection {
        path: PathBuf,
        line: usize,
        section: String,
    },
    #[error(
        "{}:{line}: \"{name}\" is outside any section; put bindings under a header such as [global] or [manual]",
        path.display()
    )]
    OutsideSection {
        path: PathBuf,
        line: usize,
        name: String,
    },
    /// The file leaves a mode with no key that quits (and stops the robot).
    #[error(
        "{}: no key quits in {mode} mode: keep q or ctrl-c bound to \"quit\" there",
        path.display()
    )]
    NoQuit { path: PathBuf, mode: String },
    #[error("{}:{line}: in [{section}]: {reason}", path.display())]
    BadKey {
        path: PathBuf,
        line: usize,
        section: String,
        reason: KeyParseError,
    },
    #[error("{}:{line}: unknown action \"{action}\" for key \"{key}\" in [{section}]", path.display())]
    UnknownAction {
        path: PathBuf,
        line: usize,
        section: String,
        key: String,
        action: String,
    },
    #[error(
        "{}:{line}: key \"{key}\" in [{section}] must name an action in quotes (e.g. \"stop\" or \"none\"), not a {found}",
        path.display()
    )]
    NotAString {
        path: PathBuf,
        line: usize,
        section: String,
        key: String,
        found: &'static str,
    },
    #[error(
        "{}:{line}: \"{key}\" in [{section}] is the same key as \"{first_key}\" on line {first_line}",
        path.display()
    )]
    Duplicate {
        path: PathBuf,
        line: usize,
        section: String,
        key: String,
        first_key: String,
        first_line: usize,
    },
}
