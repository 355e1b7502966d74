//! The real binary on a pseudo-terminal, as a user's terminal or SSH session holds it:
//! keys in, the screen out, terminal queries answered, and the terminal hung up (every
//! master descriptor closed, as sshd does when a connection drops) or the process signalled.
//! The hang-up is in hang_up.rs, for the tests that hang up.

use portable_pty::{CommandBuilder, MasterPty, PtySize, native_pty_system};
use std::fs::File;
use std::io::{Read, Write};
use std::os::fd::{AsRawFd, FromRawFd};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// Generous bound for a slow CI machine; reaching it fails the test.
pub const PATIENCE: Duration = Duration::from_secs(60);

/// How the emulated terminal answers navdeck's keyboard probe (`CSI ? u`, `CSI c`).
// Only the terminal tests ask for the kitty and the silent terminal.
#[allow(dead_code)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Terminal {
    /// A VT220: device attributes only, no kitty keyboard protocol.
    Plain,
    /// Says it speaks the kitty keyboard protocol.
    Kitty,
    /// Answers nothing at all.
    Silent,
}

pub struct Console {
    child: Option<Box<dyn portable_pty::Child + Send + Sync>>,
    /// Held (never read) so that the master side stays open until the hang-up drops it.
    pub(super) _master: Option<Box<dyn MasterPty + Send>>,
    pub(super) writer: Option<File>,
    pub(super) output: mpsc::Receiver<Vec<u8>>,
    pub(super) reader: Option<JoinHandle<()>>,
    pub(super) stop_reading: Arc<AtomicBool>,
    pub seen: Vec<u8>,
    terminal: Terminal,
    answered: bool,
    /// When the hang-up or signal that should end the console was delivered.
    pub ended_at: Option<Instant>,
}

/// A duplicate of the master side's descriptor, owned.
fn dup(master: &dyn MasterPty) -> File {
    let fd = master.as_raw_fd().expect("a unix pty has a descriptor");
    // SAFETY: dup(2) of a descriptor we hold; the new one is owned by the File alone.
    let copy = unsafe { libc::dup(fd) };
    assert!(copy >= 0, "dup failed");
    // SAFETY: `copy` is a fresh descriptor nothing else owns.
    unsafe { File::from_raw_fd(copy) }
}

impl Console {
    /// Starts navdeck with `args` (and `env`) on a 100 x 30 terminal.
    pub fn start(args: &[&str], env: &[(&str, &str)], terminal: Terminal) -> Console {
        let pty = native_pty_system()
            .openpty(PtySize {
                rows: 30,
                cols: 100,
                pixel_width: 0,
                pixel_height: 0,
            })
            .expect("a pty");
        let mut cmd = CommandBuilder::new(env!("CARGO_BIN_EXE_navdeck"));
        cmd.args(args);
        cmd.env("TERM", "xterm-256color");
        cmd.cwd(env!("CARGO_TARGET_TMPDIR"));
        for (k, v) in env {
            cmd.env(k, v);
        }
        let child = pty.slave.spawn_command(cmd).expect("navdeck starts");
        drop(pty.slave);
        let mut reader = dup(pty.master.as_ref());
        let writer = dup(pty.master.as_ref());
        let stop_reading = Arc::new(AtomicBool::new(false));
        let stop = Arc::clone(&stop_reading);
        let (tx, output) = mpsc::channel();
        let reader_thread = std::thread::spawn(move || {
            let mut buf = [0u8; 4096];
            // Polls in short slices so that a hang-up can take this descriptor away.
            while !stop.load(Ordering::SeqCst) {
                let mut fds = libc::pollfd {
                    fd: reader.as_raw_fd(),
                    events: libc::POLLIN,
                    revents: 0,
                };
                // SAFETY: one valid pollfd.
                let ready = unsafe { libc::poll(&mut fds, 1, 20) };
                if ready <= 0 {
                    continue;
                }
                match reader.read(&mut buf) {
                    Ok(n) if n > 0 => {
                        if tx.send(buf[..n].to_vec()).is_err() {
                            break;
                        }
                    }
                    _ => break,
                }
            }
        });
        Console {
            child: Some(child),
            _master: Some(pty.master),
            writer: Some(writer),
            output,
            reader: Some(reader_thread),
            stop_reading,
            seen: Vec::new(),
            terminal,
            answered: false,
            ended_at: None,
        }
    }

    /// Takes what the console wrote so far; answers its terminal queries.
    pub fn collect(&mut self, wait: Duration) {
        if let Ok(chunk) = self.output.recv_timeout(wait) {
            self.seen.extend_from_slice(&chunk);
        }
        while let Ok(chunk) = self.output.try_recv() {
            self.seen.extend_from_slice(&chunk);
        }
        if !self.answered && contains(&self.seen, b"\x1b[c") {
            self.answered = true;
            match self.terminal {
                Terminal::Plain => self.send(b"\x1b[?62;c"),
                Terminal::Kitty => self.send(b"\x1b[?0u\x1b[?62;c"),
                Terminal::Silent => {}
            }
        }
    }

    /// Reads output until `needle` has appeared.
    pub fn wait_for(&mut self, needle: &[u8]) {
        let deadline = Instant::now() + PATIENCE;
        while !contains(&self.seen, needle) {
            let left = deadline.saturating_duration_since(Instant::now());
            assert!(
                !left.is_zero(),
                "never saw {:?} in {:?}",
                String::from_utf8_lossy(needle),
                String::from_utf8_lossy(&self.seen)
            );
            self.collect(left.min(Duration::from_millis(100)));
        }
    }

    /// Sends `key` about 30 times a second, as a held key auto-repeats, until `needle`
    /// has appeared.
    pub fn hold_until(&mut self, key: &[u8], needle: &[u8]) {
        let what = format!("{:?} on screen", String::from_utf8_lossy(needle));
        self.hold_while_not(key, &what, |seen| contains(seen, needle));
    }

    /// Sends `key` about 30 times a second, as a held key auto-repeats, until `done`
    /// holds for what the console has written so far (checked between repeats).
    pub fn hold_while_not(&mut self, key: &[u8], what: &str, mut done: impl FnMut(&[u8]) -> bool) {
        let deadline = Instant::now() + PATIENCE;
        while !done(&self.seen) {
            assert!(
                Instant::now() < deadline,
                "never: {what}, holding {:?}",
                String::from_utf8_lossy(key)
            );
            self.send(key);
            self.collect(Duration::from_millis(33));
        }
    }

    pub fn send(&mut self, bytes: &[u8]) {
        let writer = self.writer.as_mut().expect("the terminal is still up");
        writer.write_all(bytes).unwrap();
        writer.flush().unwrap();
    }

    fn pid(&self) -> i32 {
        let child = self.child.as_ref().expect("still running");
        child.process_id().expect("a pid") as i32
    }

    /// Sends `signal` to navdeck.
    pub fn signal(&mut self, signal: i32) {
        self.ended_at = Some(Instant::now());
        // SAFETY: kill(2) on our own child's pid with a valid signal number.
        assert_eq!(unsafe { libc::kill(self.pid(), signal) }, 0);
    }

    /// Waits for navdeck to exit by itself; its exit code and the time it took from the
    /// hang-up or signal.
    pub fn finish(mut self) -> Finished {
        let mut child = self.child.take().expect("finished once");
        let (tx, exited) = mpsc::channel();
        std::thread::spawn(move || {
            let _ = tx.send((child.wait(), Instant::now()));
        });
        let deadline = Instant::now() + PATIENCE;
        let (status, at) = loop {
            let left = deadline.saturating_duration_since(Instant::now());
            assert!(
                !left.is_zero(),
                "navdeck did not exit; it wrote {:?}",
                String::from_utf8_lossy(&self.seen)
            );
            let wait = if self.reader.is_some() {
                self.collect(Duration::from_millis(20));
                Duration::ZERO
            } else {
                left
            };
            match exited.recv_timeout(wait) {
                Ok((status, at)) => break (status.expect("wait for navdeck"), at),
                Err(mpsc::RecvTimeoutError::Timeout) => {}
                Err(e) => panic!("waiting for navdeck: {e}"),
            }
        };
        let took = self.ended_at.map(|t| at.duration_since(t));
        if let Some(reader) = self.reader.take() {
            // The rest of the output: the reader ends at the end of the stream, which
            // comes when the last descriptor of the terminal's other side closed.
            reader.join().expect("the reader thread ends");
            while let Ok(chunk) = self.output.try_recv() {
                self.seen.extend_from_slice(&chunk);
            }
        }
        Finished {
            code: status.exit_code(),
            output: String::from_utf8_lossy(&self.seen).into_owned(),
            took,
        }
    }
}

impl Drop for Console {
    fn drop(&mut self) {
        // A failed test must not leave navdeck running.
        if let Some(child) = self.child.as_mut()
            && let Ok(None) = child.try_wait()
        {
            let _ = child.kill();
        }
        self.stop_reading.store(true, Ordering::SeqCst);
    }
}

/// How a console ended.
#[derive(Debug)]
pub struct Finished {
    pub code: u32,
    pub output: String,
    /// From the hang-up or signal to the exit, as seen from outside.
    // Read by the tests that time the ending.
    #[allow(dead_code)]
    pub took: Option<Duration>,
}

pub fn contains(haystack: &[u8], needle: &[u8]) -> bool {
    haystack.windows(needle.len()).any(|w| w == needle)
}
