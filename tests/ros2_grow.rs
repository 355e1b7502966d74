//! A ROS 2 robot's console on a real terminal watches its domain: a robot that appears is
//! offered in the log, and `:robot add NS` makes the console a fleet of two, each robot
//! stopped and named when it ends.

use crate::pty_support;
use crate::ros2_support;

use pty_support::{Console, Terminal};
use ros2_support::{FakeOptions, FakeRobot};

#[test]
fn a_robot_that_appears_is_offered_and_joins_the_console_as_a_fleet() {
    // The console drives /tb3_0 (silent here); a robot publishing at the root appears.
    let _robot = FakeRobot::start(FakeOptions::new(70));
    let logs = crate::common::scratch::scratch("grow-logs");
    let logs_arg = logs.to_str().unwrap();
    let args = [
        "--link",
        "ros2",
        "--domain",
        "70",
        "--ns",
        "/tb3_0",
        "--log-dir",
        logs_arg,
    ];
    let mut console = Console::start(&args, &[], Terminal::Plain);
    console.wait_for(b"Status");
    // The screen is drawn as differences: the log's file says the line whole.
    in_a_log(
        &mut console,
        &logs,
        "robot / appeared on the domain: :robot add / drives it",
    );
    // No fleet panel while the console drives one robot.
    assert!(!pty_support::contains(&console.seen, b"Fleet:"));
    console.send(b":robot add /\r");
    in_a_log(&mut console, &logs, "robot / joined: 2 robots");
    console.wait_for(b"Fleet: 2 robots");
    console.send(b"q");
    let end = console.finish();
    assert_eq!(end.code, 0, "{}", end.output);
    assert!(
        end.output.contains("ros2 d70 /tb3_0") && end.output.contains(", / on ros2 d70 /"),
        "both robots named as stopped: {}",
        end.output
    );
    assert_eq!(
        end.output.matches("session log in ").count(),
        2,
        "{}",
        end.output
    );
}

/// Waits (reading the console's output meanwhile) until a log file in `dir` holds `line`.
fn in_a_log(console: &mut Console, dir: &std::path::Path, line: &str) {
    let started = std::time::Instant::now();
    loop {
        let found = (std::fs::read_dir(dir).unwrap().flatten())
            .any(|f| std::fs::read_to_string(f.path()).is_ok_and(|t| t.contains(line)));
        if found {
            return;
        }
        assert!(started.elapsed().as_secs() < 30, "no log holds {line:?}");
        console.collect(std::time::Duration::from_millis(50));
    }
}
