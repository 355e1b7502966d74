//! The exact bytes terminals send, through navdeck's decoder into the console, and the
//! motion the robot is commanded: releases from terminals speaking the kitty keyboard
//! protocol stop the robot at once; terminals that never send a release (tmux, or one
//! that answered the probe and then sends none) are governed by the deadman.

use crate::common;

use navdeck::app::App;
use navdeck::tui::input::{Input, InputDecoder};
use std::collections::VecDeque;

/// Auto-repeat period of a typical terminal.
const REPEAT: f64 = 1.0 / 30.0;
/// The console's control period in these tests.
const TICK: f64 = 0.01;

struct Keyboard {
    app: App,
    decoder: InputDecoder,
    t: f64,
}

impl Keyboard {
    fn new() -> Keyboard {
        Keyboard {
            app: common::default_app(),
            decoder: InputDecoder::default(),
            t: 0.0,
        }
    }

    /// One read's worth of bytes from the terminal, at the current time.
    fn bytes(&mut self, bytes: &[u8]) {
        let mut inputs = VecDeque::new();
        self.decoder.feed(bytes, &mut inputs);
        for input in inputs {
            if let Input::Key(key, kind) = input {
                self.app.handle_key(key, kind, self.t);
            }
        }
        self.app.update(self.t);
    }

    /// Lets `seconds` pass, the console ticking.
    fn wait(&mut self, seconds: f64) {
        let end = self.t + seconds;
        while self.t < end - 1e-9 {
            self.t = (self.t + TICK).min(end);
            self.app.update(self.t);
        }
    }

    /// A key held for `seconds`: the first bytes, then `repeat` bytes at the auto-repeat rate.
    fn hold(&mut self, first: &[u8], repeat: &[u8], seconds: f64) {
        self.bytes(first);
        let end = self.t + seconds;
        while self.t + REPEAT <= end + 1e-9 {
            self.wait(REPEAT);
            self.bytes(repeat);
        }
    }

    fn driving(&self) -> bool {
        self.app.pilot().commanded().linear > 0.0
    }

    fn deadman(&self) -> f64 {
        self.app.config().teleop.deadman_timeout
    }
}

/// kitty protocol, all keys as escape codes with event types: w pressed, repeated, released.
const W_PRESS: &[u8] = b"\x1b[119u";
const W_REPEAT: &[u8] = b"\x1b[119;1:2u";
const W_RELEASE: &[u8] = b"\x1b[119;1:3u";
/// The probe's replies from a terminal that says it speaks the kitty protocol.
const KITTY_REPLY: &[u8] = b"\x1b[?0u\x1b[?62;22c";

#[test]
fn a_kitty_release_stops_the_robot_at_once() {
    let mut k = Keyboard::new();
    k.bytes(KITTY_REPLY);
    k.hold(W_PRESS, W_REPEAT, 1.0);
    assert!(k.driving(), "holding w drives");
    k.bytes(W_RELEASE);
    assert!(!k.driving(), "the release stops the robot in the same tick");
}

#[test]
fn legacy_bytes_drive_until_the_deadman() {
    let mut k = Keyboard::new();
    k.hold(b"w", b"w", 1.0);
    let deadman = k.deadman();
    k.wait(deadman * 0.5);
    assert!(k.driving(), "still inside the deadman");
    k.wait(deadman * 0.5 + 0.05);
    assert!(!k.driving(), "stopped by the deadman");
}

/// tmux (and terminals with a broken implementation) may answer the probe "supported"
/// and then never send a release: the deadman still stops the robot.
#[test]
fn a_terminal_that_claims_releases_but_sends_none_is_stopped_by_the_deadman() {
    let mut k = Keyboard::new();
    k.bytes(KITTY_REPLY);
    k.hold(W_PRESS, W_REPEAT, 1.0);
    let deadman = k.deadman();
    k.wait(deadman + 0.05);
    assert!(
        !k.driving(),
        "no release came, the deadman stopped the robot"
    );
}

/// Until a release has been seen, a single press gets the plain deadman; once one has,
/// a press not yet repeating is given the terminal's repeat delay, since its release
/// will come.
#[test]
fn releases_are_trusted_only_once_one_has_arrived() {
    let mut k = Keyboard::new();
    k.bytes(KITTY_REPLY);
    k.bytes(W_PRESS);
    let deadman = k.deadman();
    k.wait(deadman + 0.05);
    assert!(
        !k.driving(),
        "the probe's answer alone does not suspend the deadman"
    );
    k.bytes(W_RELEASE);
    k.wait(0.5);
    // A release has been seen: the next single press rides out the repeat delay.
    k.bytes(W_PRESS);
    k.wait(deadman + 0.05);
    assert!(
        k.driving(),
        "a press awaiting its first repeat keeps driving"
    );
    k.bytes(W_RELEASE);
    assert!(!k.driving());
}

/// With only DISAMBIGUATE_ESCAPE_CODES | REPORT_EVENT_TYPES a terminal sends a release of
/// Backspace (and Enter, Tab) as the same byte as a press; navdeck asks for every key as
/// an escape code, so the release is told apart.
#[test]
fn backspace_release_as_an_escape_code_is_not_a_second_press() {
    let mut k = Keyboard::new();
    k.bytes(b":gotoo");
    assert_eq!(k.app.prompt(), Some("gotoo"));
    // As the reduced flags deliver press and release: the same byte twice.
    k.bytes(b"\x7f\x7f");
    assert_eq!(
        k.app.prompt(),
        Some("got"),
        "the release counted as a press"
    );
    // As navdeck's flags deliver them: press and release told apart.
    k.bytes(b"oo\x1b[127u\x1b[127;1:3u");
    assert_eq!(k.app.prompt(), Some("goto"));
    k.bytes(b"\x1b[13u\x1b[13;1:3u");
    assert_eq!(k.app.prompt(), None, "enter ran the command once");
}

#[test]
fn ctrl_c_as_a_kitty_escape_code_quits() {
    let mut k = Keyboard::new();
    k.hold(W_PRESS, W_REPEAT, 0.5);
    k.bytes(b"\x1b[99;5u");
    assert!(k.app.should_quit());
    assert!(!k.driving());
}
