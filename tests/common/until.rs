//! Bounded waits for what another thread or process does, when there is no event to wait on.

use std::time::{Duration, Instant};

/// Generous bound for a slow machine; reaching it fails the test.
const PATIENCE: Duration = Duration::from_secs(20);

/// Checks `done` every few milliseconds until it holds, failing the test after PATIENCE.
pub fn until(what: &str, mut done: impl FnMut() -> bool) {
    let give_up = Instant::now() + PATIENCE;
    while !done() {
        assert!(Instant::now() < give_up, "gave up waiting for {what}");
        std::thread::sleep(Duration::from_millis(5));
    }
}
