//! The terminal hung up under a console, as sshd hangs it up when a connection drops.

use super::console::Console;
use std::sync::atomic::Ordering;
use std::time::Instant;

impl Console {
    /// The terminal goes away as it does when an SSH connection drops: every descriptor
    /// of the master side is closed, and the kernel hangs up the session.
    pub fn hang_up(&mut self) {
        self.stop_reading.store(true, Ordering::SeqCst);
        if let Some(reader) = self.reader.take() {
            reader.join().expect("the reader thread ends");
        }
        while let Ok(chunk) = self.output.try_recv() {
            self.seen.extend_from_slice(&chunk);
        }
        self.writer = None;
        self._master = None;
        self.ended_at = Some(Instant::now());
    }
}
