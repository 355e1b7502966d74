//! How a link's task wakes the console: a byte on a socket the console's input wait polls
//! beside the terminal and the signals, so terminal input, link events and the tick timer
//! are waited on in one place. Only what the console acts on at once wakes it (a goal or a
//! pose from RViz, a port lost or found again, a warning); sensor streams wait in their
//! inboxes for the control tick.

use std::io::{Read, Write};
use std::os::fd::{AsFd, BorrowedFd};
use std::os::unix::net::UnixStream;
use std::sync::OnceLock;

/// A wake socket: `notify` from any thread, `fd` to poll, `drain` after waking.
pub struct Wake {
    readable: UnixStream,
    writable: UnixStream,
}

impl Wake {
    pub fn new() -> std::io::Result<Self> {
        let (readable, writable) = UnixStream::pair()?;
        readable.set_nonblocking(true)?;
        writable.set_nonblocking(true)?;
        Ok(Self { readable, writable })
    }

    /// Makes the socket readable. A full socket already holds a wake: nothing is lost.
    pub fn notify(&self) {
        let _ = (&self.writable).write(&[1]);
    }

    pub fn fd(&self) -> BorrowedFd<'_> {
        self.readable.as_fd()
    }

    /// Empties the socket; the number of wakes it held.
    pub fn drain(&self) -> usize {
        let mut buf = [0u8; 64];
        let mut total = 0;
        while let Ok(n @ 1..) = (&self.readable).read(&mut buf) {
            total += n;
        }
        total
    }
}

static GLOBAL: OnceLock<Option<Wake>> = OnceLock::new();

/// The process's wake, which every link notifies; None if no socket could be made (the
/// console then runs on its tick alone).
pub fn global() -> Option<&'static Wake> {
    GLOBAL.get_or_init(|| Wake::new().ok()).as_ref()
}

/// Wakes the console.
pub fn notify() {
    if let Some(wake) = global() {
        wake.notify();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_notify_is_held_until_drained() {
        let wake = Wake::new().unwrap();
        assert_eq!(wake.drain(), 0);
        wake.notify();
        wake.notify();
        assert_eq!(wake.drain(), 2);
        assert_eq!(wake.drain(), 0);
    }

    #[test]
    fn notifies_from_other_threads_arrive() {
        let wake = std::sync::Arc::new(Wake::new().unwrap());
        let other = std::sync::Arc::clone(&wake);
        std::thread::spawn(move || other.notify()).join().unwrap();
        assert_eq!(wake.drain(), 1);
    }
}
