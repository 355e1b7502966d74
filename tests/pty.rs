//! The real binary in a pseudo-terminal: it draws, drives, quits on `q` and on SIGTERM,
//! and leaves the terminal as it found it.

use portable_pty::{CommandBuilder, PtySize, native_pty_system};
use std::io::{Read, Write};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// Generous bound for a slow CI machine; reaching it fails the test.
const PATIENCE: Duration = Duration::from_secs(60);

struct Console {
    child: Box<dyn portable_pty::Child + Send + Sync>,
    writer: Box<dyn Write + Send>,
    output: mpsc::Receiver<Vec<u8>>,
    seen: Vec<u8>,
}

impl Console {
    fn start() -> Console {
        let pty = native_pty_system()
            .openpty(PtySize {
                rows: 30,
                cols: 100,
                pixel_width: 0,
                pixel_height: 0,
            })
            .expect("a pty");
        let mut cmd = CommandBuilder::new(env!("CARGO_BIN_EXE_navdeck"));
        cmd.env("TERM", "xterm-256color");
        let child = pty.slave.spawn_command(cmd).expect("navdeck starts");
        drop(pty.slave);
        let mut reader = pty.master.try_clone_reader().unwrap();
        let writer = pty.master.take_writer().unwrap();
        let (tx, output) = mpsc::channel();
        std::thread::spawn(move || {
            let _keep_master = pty.master;
            let mut buf = [0u8; 4096];
            while let Ok(n) = reader.read(&mut buf) {
                if n == 0 || tx.send(buf[..n].to_vec()).is_err() {
                    break;
                }
            }
        });
        Console {
            child,
            writer,
            output,
            seen: Vec::new(),
        }
    }

    /// Reads output until `needle` has appeared; answers terminal queries on the way.
    fn wait_for(&mut self, needle: &[u8]) {
        let deadline = Instant::now() + PATIENCE;
        let mut answered = false;
        while !contains(&self.seen, needle) {
            let left = deadline.saturating_duration_since(Instant::now());
            assert!(
                !left.is_zero(),
                "never saw {:?}",
                String::from_utf8_lossy(needle)
            );
            if let Ok(chunk) = self.output.recv_timeout(left) {
                self.seen.extend_from_slice(&chunk);
            }
            // crossterm asks for the keyboard protocol and device attributes: answer
            // as a plain VT220 would, so it goes on without the kitty protocol.
            if !answered && contains(&self.seen, b"\x1b[c") {
                answered = true;
                self.writer.write_all(b"\x1b[?62;c").unwrap();
            }
        }
    }

    fn send(&mut self, bytes: &[u8]) {
        self.writer.write_all(bytes).unwrap();
        self.writer.flush().unwrap();
    }

    /// Waits for the child to exit (it must, by itself) and collects the rest of its output.
    fn finish(mut self) -> (u32, String) {
        let deadline = Instant::now() + PATIENCE;
        let status = loop {
            if let Some(status) = self.child.try_wait().unwrap() {
                break status;
            }
            assert!(Instant::now() < deadline, "navdeck did not exit");
            if let Ok(chunk) = self.output.recv_timeout(Duration::from_millis(50)) {
                self.seen.extend_from_slice(&chunk);
            }
        };
        while let Ok(chunk) = self.output.recv_timeout(Duration::from_millis(200)) {
            self.seen.extend_from_slice(&chunk);
        }
        (
            status.exit_code(),
            String::from_utf8_lossy(&self.seen).into_owned(),
        )
    }
}

fn contains(haystack: &[u8], needle: &[u8]) -> bool {
    haystack.windows(needle.len()).any(|w| w == needle)
}

#[test]
fn console_draws_drives_and_quits_restoring_the_terminal() {
    let mut console = Console::start();
    console.wait_for(b"Status");
    console.wait_for(b"MANUAL");
    for _ in 0..10 {
        console.send(b"w");
    }
    console.wait_for(b"forward");
    console.send(b"q");
    let (code, out) = console.finish();
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("\x1b[?1049l"), "alternate screen not left");
    assert!(out.contains("\x1b[?25h"), "cursor not shown again");
    assert!(out.contains("stopped; quit by user"), "{out}");
}

#[test]
fn sigterm_stops_the_robot_and_restores_the_terminal() {
    let mut console = Console::start();
    console.wait_for(b"Status");
    console.send(b"wwww");
    console.wait_for(b"forward");
    let pid = console.child.process_id().expect("a pid") as i32;
    // SAFETY: kill(2) on our own child's pid with a valid signal number.
    assert_eq!(unsafe { libc::kill(pid, libc::SIGTERM) }, 0);
    let (code, out) = console.finish();
    assert_eq!(code, 128 + 15, "{out}");
    assert!(out.contains("\x1b[?1049l"), "alternate screen not left");
    assert!(out.contains("SIGTERM received"), "{out}");
}
