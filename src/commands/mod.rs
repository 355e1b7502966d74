//! One module per subcommand, and the console (no subcommand) in `console`.

/// Writes to standard output. A reader that has gone (`navdeck map show ... | head`, a
/// dropped SSH session) is no reason to panic: what it no longer reads is lost, nothing
/// else. Control characters (from a world's name, say) reach the terminal escaped.
macro_rules! say {
    ($($arg:tt)*) => {{
        let text = navdeck::data::printable::printable(&format!($($arg)*), None);
        let _ = write!(std::io::stdout(), "{text}");
    }};
}

/// `say!` with a newline.
macro_rules! sayln {
    ($($arg:tt)*) => {{
        let text = navdeck::data::printable::printable(&format!($($arg)*), None);
        let _ = writeln!(std::io::stdout(), "{text}");
    }};
}

/// A line on standard error, which may have gone with the terminal: escaped as `say!`
/// is, and each line cut to `ERROR_LINE` characters (an error may quote a whole input).
macro_rules! say_err {
    ($($arg:tt)*) => {{
        let text = navdeck::data::printable::printable(&format!($($arg)*), Some($crate::commands::ERROR_LINE));
        let _ = writeln!(std::io::stderr(), "{text}");
    }};
}

/// Characters of an error line shown.
pub(crate) const ERROR_LINE: usize = 400;

pub(crate) mod args;
pub(crate) mod arm;
pub(crate) mod console;
pub(crate) mod fleet;
pub(crate) mod lane;
pub(crate) mod map;
pub(crate) mod mission;
pub(crate) mod mission_fleet;
pub(crate) mod plan;
pub(crate) mod replay;
pub(crate) mod replay_fleet;
pub(crate) mod ros2;
pub(crate) mod ros2_robots;
pub(crate) mod route;
pub(crate) mod sweep;
pub(crate) mod tags;
pub(crate) mod tour;
pub(crate) mod twin_args;
pub(crate) mod world;
