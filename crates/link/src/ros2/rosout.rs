//! /rosout both ways: the console's log lines out as rcl_interfaces/Log under navdeck's
//! node name, and the robot's nodes' lines in, for the log pane.

use crate::Notice;
use navdeck_core::data::Level;
use navdeck_msgs::ros as msgs;

/// rcl_interfaces/Log's severities (its DEBUG..FATAL constants).
pub const DEBUG: u8 = 10;
pub const INFO: u8 = 20;
pub const WARN: u8 = 30;
pub const ERROR: u8 = 40;
pub const FATAL: u8 = 50;

/// A console level as rcl_interfaces/Log carries it (a success is news, not a warning).
pub fn severity(level: Level) -> u8 {
    match level {
        Level::Info | Level::Success => INFO,
        Level::Warn => WARN,
        Level::Error => ERROR,
    }
}

/// A /rosout severity as a console level: DEBUG and INFO are routine, FATAL an error.
pub fn level(severity: u8) -> Level {
    match severity {
        ..=INFO => Level::Info,
        21..=WARN => Level::Warn,
        _ => Level::Error,
    }
}

/// The logger name rcl gives a node: its namespace and name joined by dots
/// ("/tb3" + "navdeck" is "tb3.navdeck").
pub fn logger_name(namespace: &str, node: &str) -> String {
    namespace
        .split('/')
        .filter(|s| !s.is_empty())
        .chain(std::iter::once(node))
        .collect::<Vec<_>>()
        .join(".")
}

/// A console line as /rosout carries it.
pub fn log_message(stamp: msgs::Time, level: Level, logger: &str, text: &str) -> msgs::Log {
    msgs::Log {
        stamp,
        level: severity(level),
        name: logger.to_string(),
        msg: text.to_string(),
        ..msgs::Log::default()
    }
}

/// Which of the robot's /rosout lines reach the console: not navdeck's own (they come
/// back on the same topic), nor another console's, nor those below `lowest`. Under a
/// namespace, a node in another namespace belongs to another robot of the fleet: its
/// lines are that robot's, not this one's.
pub fn wanted(msg: &msgs::Log, own_logger: &str, lowest: u8) -> Option<Notice> {
    let (own_ns, node) = own_logger.rsplit_once('.').unwrap_or(("", own_logger));
    let (ns, name) = msg.name.rsplit_once('.').unwrap_or(("", &msg.name));
    let another_robots = !own_ns.is_empty() && !ns.is_empty() && ns != own_ns;
    if name == node || another_robots || msg.level < lowest {
        return None;
    }
    Some(Notice {
        level: level(msg.level),
        text: msg.msg.clone(),
        source: Some(msg.name.clone()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_map_both_ways() {
        assert_eq!(severity(Level::Success), INFO);
        assert_eq!(severity(Level::Warn), WARN);
        assert_eq!(severity(Level::Error), ERROR);
        assert_eq!(level(DEBUG), Level::Info);
        assert_eq!(level(WARN), Level::Warn);
        assert_eq!(level(FATAL), Level::Error);
        for l in [Level::Info, Level::Warn, Level::Error] {
            assert_eq!(level(severity(l)), l);
        }
    }

    #[test]
    fn logger_names_join_the_namespace_with_dots() {
        assert_eq!(logger_name("/", "navdeck"), "navdeck");
        assert_eq!(logger_name("/tb3", "navdeck"), "tb3.navdeck");
        assert_eq!(logger_name("/a/b/", "n"), "a.b.n");
    }

    #[test]
    fn own_lines_and_quiet_ones_are_left_out() {
        let line = |name: &str, level| msgs::Log {
            level,
            name: name.into(),
            msg: "battery low".into(),
            ..msgs::Log::default()
        };
        assert_eq!(wanted(&line("navdeck", WARN), "navdeck", INFO), None);
        assert_eq!(
            wanted(&line("turtlebot3_node", DEBUG), "navdeck", INFO),
            None
        );
        let n = wanted(&line("turtlebot3_node", WARN), "navdeck", INFO).unwrap();
        assert_eq!(n.level, Level::Warn);
        assert_eq!(n.source.as_deref(), Some("turtlebot3_node"));
        assert_eq!(n.text, "battery low");
    }

    #[test]
    fn under_a_namespace_other_robots_and_other_consoles_are_left_out() {
        let line = |name: &str| msgs::Log {
            level: WARN,
            name: name.into(),
            msg: "battery low".into(),
            ..msgs::Log::default()
        };
        let own = logger_name("/tb3_0", "navdeck");
        assert!(wanted(&line("tb3_0.turtlebot3_node"), &own, INFO).is_some());
        assert!(wanted(&line("turtlebot3_node"), &own, INFO).is_some());
        assert_eq!(wanted(&line("tb3_1.turtlebot3_node"), &own, INFO), None);
        assert_eq!(wanted(&line("tb3_1.navdeck"), &own, INFO), None);
        // Without a namespace every robot node is this robot's; other consoles are not.
        assert!(wanted(&line("tb3_1.turtlebot3_node"), "navdeck", INFO).is_some());
        assert_eq!(wanted(&line("tb3_1.navdeck"), "navdeck", INFO), None);
    }
}
