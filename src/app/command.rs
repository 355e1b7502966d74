//! The command line (`:`): what a typed command means.

use crate::control::config::ControllerKind;
use crate::geometry::Point2;

/// A parsed command.
#[derive(Clone, Debug, PartialEq)]
pub enum Command {
    /// `goto X Y`: plan to a point of the map frame, metres.
    GotoPoint(Point2),
    /// `goto marker ID`: plan to a landmark's approach point.
    GotoMarker(u32),
    /// `controller NAME`.
    Controller(ControllerKind),
    /// `clear`: forget the planned path.
    Clear,
    /// `save NAME`: save the map as NAME.yaml + NAME.pgm in the maps folder.
    Save(String),
}

pub const USAGE: &str =
    "goto X Y | goto marker ID | controller pid|pure_pursuit|hybrid | clear | save NAME";

/// Reads one command line, or says what is wrong with it.
pub fn parse(line: &str) -> Result<Command, String> {
    let words: Vec<&str> = line.split_whitespace().collect();
    match words.as_slice() {
        ["goto", "marker", id] => id
            .parse()
            .map(Command::GotoMarker)
            .map_err(|_| format!("goto marker: `{id}` is not a marker ID")),
        ["goto", x, y] => {
            let coord = |s: &str| {
                s.trim_end_matches(',')
                    .parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| format!("goto: `{s}` is not a number of metres"))
            };
            Ok(Command::GotoPoint(Point2::new(coord(x)?, coord(y)?)))
        }
        ["goto", ..] => Err("goto wants X Y in metres, or marker ID".to_string()),
        ["controller", name] => name
            .parse()
            .map(Command::Controller)
            .map_err(|e: crate::control::config::UnknownController| e.to_string()),
        ["clear"] => Ok(Command::Clear),
        ["save", name] => Ok(Command::Save(name.to_string())),
        ["save", ..] => Err("save wants one NAME (letters, digits, - and _)".to_string()),
        [] => Err(format!("empty command; try {USAGE}")),
        [other, ..] => Err(format!("unknown command `{other}`; try {USAGE}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_issue_examples() {
        assert_eq!(
            parse("goto 1.20 -0.50"),
            Ok(Command::GotoPoint(Point2::new(1.2, -0.5)))
        );
        assert_eq!(parse("goto marker 421"), Ok(Command::GotoMarker(421)));
        assert_eq!(
            parse("controller pid"),
            Ok(Command::Controller(ControllerKind::Pid))
        );
    }

    #[test]
    fn bad_input_names_the_value() {
        assert!(parse("goto 1.2 north").unwrap_err().contains("`north`"));
        assert!(parse("goto 1e400 0").unwrap_err().contains("1e400"));
        assert!(parse("fly 1 2").unwrap_err().contains("`fly`"));
        assert!(parse("controller lqr").unwrap_err().contains("lqr"));
    }
}
