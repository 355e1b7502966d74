//! Signals that end the console (SIGINT, SIGTERM, SIGHUP on an SSH drop) and SIGWINCH,
//! each recorded in a flag and written as a byte to a socket the input loop polls, so a
//! signal wakes the loop at once however long it was going to wait.
//!
//! Once the robot has been told to stop (`arm_immediate_exit`), a further terminating
//! signal ends the process at once with 128 + its number, as shells expect.

use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM, SIGWINCH};
use std::io::{self, Read};
use std::os::fd::{AsFd, BorrowedFd};
use std::os::unix::net::UnixStream;
use std::sync::Arc;
use std::sync::atomic::Ordering::SeqCst;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Duration;

/// The signals that end navdeck.
pub const TERMINATING: [i32; 3] = [SIGINT, SIGTERM, SIGHUP];

/// Watches the terminating signals and window size changes.
pub struct Signals {
    pending: Arc<AtomicUsize>,
    resized: Arc<AtomicBool>,
    stopping: Arc<AtomicBool>,
    wake: UnixStream,
}

impl Signals {
    /// Installs the handlers. Call once, before the terminal is touched.
    pub fn watch() -> io::Result<Self> {
        let pending = Arc::new(AtomicUsize::new(0));
        let resized = Arc::new(AtomicBool::new(false));
        let stopping = Arc::new(AtomicBool::new(false));
        let (wake, notify) = UnixStream::pair()?;
        wake.set_nonblocking(true)?;
        notify.set_nonblocking(true)?;
        for signal in TERMINATING {
            // The immediate exit must be registered before the flag it reads is set
            // (signal-hook runs a signal's actions in order of registration).
            signal_hook::flag::register_conditional_shutdown(
                signal,
                128 + signal,
                Arc::clone(&stopping),
            )?;
            let first = Arc::clone(&pending);
            // SAFETY: the action is one atomic compare-and-swap, which is async-signal-safe.
            // The first signal's number is kept: it names the exit status.
            unsafe {
                signal_hook::low_level::register(signal, move || {
                    let _ = first.compare_exchange(0, signal as usize, SeqCst, SeqCst);
                })
            }?;
            signal_hook::low_level::pipe::register(signal, notify.try_clone()?)?;
        }
        signal_hook::flag::register(SIGWINCH, Arc::clone(&resized))?;
        signal_hook::low_level::pipe::register(SIGWINCH, notify)?;
        Ok(Self {
            pending,
            resized,
            stopping,
            wake,
        })
    }

    /// The number of the first terminating signal received, if any.
    pub fn pending(&self) -> Option<usize> {
        match self.pending.load(Ordering::SeqCst) {
            0 => None,
            n => Some(n),
        }
    }

    /// The cell the handlers write the signal number to (0: none yet).
    pub fn cell(&self) -> &AtomicUsize {
        &self.pending
    }

    /// Whether the window changed size since the last call.
    pub fn take_resized(&self) -> bool {
        self.resized.swap(false, Ordering::SeqCst)
    }

    /// What the input loop polls: readable after any watched signal.
    pub fn wake_fd(&self) -> BorrowedFd<'_> {
        self.wake.as_fd()
    }

    /// Empties the wake socket after the loop woke.
    pub fn drain(&self) {
        let mut buf = [0u8; 64];
        while matches!((&self.wake).read(&mut buf), Ok(n) if n > 0) {}
    }

    /// The robot has been told to stop: from now on a terminating signal ends the process
    /// at once, and the process ends by itself `deadline` from now whatever it is waiting
    /// on (a terminal that no longer drains output, a link that does not close), with
    /// `code`.
    pub fn arm_immediate_exit(&self, deadline: Duration, code: i32) {
        if self.stopping.swap(true, Ordering::SeqCst) {
            return;
        }
        let spawned = std::thread::Builder::new()
            .name("exit deadline".into())
            .spawn(move || {
                std::thread::sleep(deadline);
                signal_hook::low_level::exit(code);
            });
        // Without the thread the exit is unbounded but still happens: nothing to undo.
        drop(spawned);
    }
}

/// The conventional name of a signal number.
pub fn signal_name(signal: usize) -> String {
    match signal as i32 {
        SIGHUP => "SIGHUP".into(),
        SIGINT => "SIGINT".into(),
        SIGTERM => "SIGTERM".into(),
        n => n.to_string(),
    }
}
