//! The real binary in a pseudo-terminal: it draws, drives, quits on `q` and on SIGTERM,
//! and leaves the terminal as it found it.

mod pty_support;

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
