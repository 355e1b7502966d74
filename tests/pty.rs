//! The real binary in a pseudo-terminal: it draws, drives, quits on `q` and on SIGTERM,
//! and leaves the terminal as it found it.

use crate::pty_support;

use pty_support::{Console, Terminal};

#[test]
fn console_draws_drives_and_quits_restoring_the_terminal() {
    let mut console = Console::start(&[], &[], Terminal::Plain);
    console.wait_for(b"Status");
    console.wait_for(b"MANUAL");
    for _ in 0..10 {
        console.send(b"w");
    }
    console.wait_for(b"forward");
    console.send(b"q");
    let end = console.finish();
    assert_eq!(end.code, 0, "{}", end.output);
    assert!(
        end.output.contains("\x1b[?1049l"),
        "alternate screen not left"
    );
    assert!(end.output.contains("\x1b[?25h"), "cursor not shown again");
    assert!(
        end.output.contains("stopped; quit by user"),
        "{}",
        end.output
    );
    // The session's log is on disk, named at exit, with what the screen's log showed.
    let named = end
        .output
        .split("session log in ")
        .nth(1)
        .and_then(|rest| rest.split_whitespace().next())
        .unwrap_or_else(|| panic!("no log file named: {}", end.output));
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(named);
    let text = std::fs::read_to_string(&path).expect("the log file");
    assert!(
        text.contains("INFO mode MANUAL") || text.contains("keymap"),
        "{text}"
    );
    assert!(
        text.lines()
            .all(|l| l.len() > 13 && l.as_bytes()[2] == b':'),
        "{text}"
    );
}

#[test]
fn sigterm_stops_the_robot_and_restores_the_terminal() {
    let mut console = Console::start(&[], &[], Terminal::Plain);
    console.wait_for(b"Status");
    console.send(b"wwww");
    console.wait_for(b"forward");
    console.signal(libc::SIGTERM);
    let end = console.finish();
    assert_eq!(end.code, 128 + 15, "{}", end.output);
    assert!(
        end.output.contains("\x1b[?1049l"),
        "alternate screen not left"
    );
    assert!(end.output.contains("SIGTERM received"), "{}", end.output);
}

/// A terminal that answers the probe as kitty's does is asked for releases of every key
/// as escape codes, and the request is taken back on exit; a kitty release stops the robot.
#[test]
fn a_kitty_terminal_is_asked_for_key_releases_and_given_its_keyboard_back() {
    let mut console = Console::start(&[], &[], Terminal::Kitty);
    console.wait_for(b"Status");
    // DISAMBIGUATE | REPORT_EVENT_TYPES | REPORT_ALTERNATE_KEYS | REPORT_ALL_KEYS_AS_ESCAPE_CODES
    console.wait_for(b"\x1b[>15u");
    console.hold_until(b"\x1b[119;1:2u", b"forward");
    console.send(b"\x1b[119;1:3u\x1b[113u\x1b[113;1:3u");
    let end = console.finish();
    assert_eq!(end.code, 0, "{}", end.output);
    assert!(end.output.contains("\x1b[<1u"), "keyboard flags not popped");
}

/// A terminal that answers nothing: the console comes up and works all the same (the
/// probe waits for no answer).
#[test]
fn a_silent_terminal_does_not_hold_up_the_console() {
    let mut console = Console::start(&[], &[], Terminal::Silent);
    console.wait_for(b"Status");
    console.hold_until(b"w", b"forward");
    console.send(b"q");
    let end = console.finish();
    assert_eq!(end.code, 0, "{}", end.output);
    assert!(!end.output.contains("\x1b[>15u"), "flags pushed unasked");
}
