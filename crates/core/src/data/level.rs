//! How much a log line matters: one scale for the console, the mission and the links.

/// How much a log line matters; the TUI colours by level.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Level {
    Info,
    /// Progress worth celebrating, seed 001's `[green]` lines.
    Success,
    /// Seed 001's `[red]Warning!` lines: overruns, refusals.
    Warn,
    Error,
}

impl Level {
    pub fn tag(self) -> &'static str {
        match self {
            Level::Info => "INFO",
            Level::Success => " OK ",
            Level::Warn => "WARN",
            Level::Error => "ERR ",
        }
    }
}
