//! A ROSArduinoBridge firmware on a pseudo-terminal, for tests: the commands navdeck uses,
//! the 30 Hz PID frame with a first-order wheel model, the 2 s auto-stop, 16 servos that
//! sweep (every write recorded), the time bytes take at the baud rate, and switches for
//! faults (garbage, a dropped or slow reply, an encoder jump, unplugging and plugging back
//! in).
//!
//! The device path handed to navdeck is a symlink to the terminal's slave side, so
//! unplugging can remove it and plugging back in can point it at a new terminal, as a USB
//! adapter re-enumerating does.
//!
//! A file each beside this one, for the tests that use them: the fault switches
//! (faults.rs), the firmware hanging (mute.rs), the motor requests read back
//! (requests.rs), and waiting for PID frames and setting the encoder counts (frames.rs).

use std::os::fd::{AsRawFd, FromRawFd, OwnedFd};
use std::path::PathBuf;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::mpsc::{Receiver, Sender, channel};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// The firmware's PID rate, frames per second (PID_RATE).
pub const PID_RATE: f64 = 30.0;
/// The firmware stops the motors this long after the last motor command (AUTO_STOP_INTERVAL).
pub const AUTO_STOP: Duration = Duration::from_millis(2000);
/// Fraction of the gap to the target speed the wheels close each frame.
const RESPONSE: f64 = 0.5;
/// Ticks per frame at full PWM for `o`.
const FULL_PWM_TICKS: f64 = 40.0;
/// Degrees a servo sweeps per frame.
const SERVO_STEP: f64 = 6.0;
/// Servos the board drives (`s`/`t` indices 0..SERVOS), as on a 16-channel servo board.
pub const SERVOS: usize = 16;
/// Generous bound for a slow machine; reaching it fails the test.
pub const PATIENCE: Duration = Duration::from_secs(20);

/// What the emulated firmware has and how it talks.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    pub baud: u32,
    /// Built with USE_SERVOS.
    pub servos: bool,
    /// Reads requests but never answers (wrong sketch, wrong baud rate).
    pub silent: bool,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            baud: 57600,
            servos: true,
            silent: false,
        }
    }
}

/// What the firmware has seen and done; tests read it.
#[derive(Debug)]
pub struct State {
    /// Every request line received, in order, without its CR.
    pub requests: Vec<String>,
    /// Encoder positions, counts (reported as wrapping `long`s).
    pub left: f64,
    pub right: f64,
    pub target: (i32, i32),
    pub moving: bool,
    pub auto_stops: u32,
    pub servo_angle: [f64; SERVOS],
    /// Every `s IDX DEG` accepted, in order: (index, degrees as sent, before clamping).
    pub servo_writes: Vec<(usize, i64)>,
    pub plugged: bool,
    /// PID frames run since start.
    pub frames: u64,
    raw: Option<(f64, f64)>,
    speed: (f64, f64),
    servo_target: [f64; SERVOS],
    last_motor: Instant,
    start: Instant,
    pub(super) garbage: Option<Vec<u8>>,
    pub(super) drop_next: bool,
    pub(super) delay_next: Option<Duration>,
    /// Reads requests and answers none from now on (a firmware that hung).
    pub(super) muted: bool,
}

impl State {
    pub fn counts(&self) -> (i32, i32) {
        (wrap(self.left), wrap(self.right))
    }

    fn reset(&mut self) {
        self.left = 0.0;
        self.right = 0.0;
        self.target = (0, 0);
        self.moving = false;
        self.raw = None;
        self.speed = (0.0, 0.0);
    }

    /// Runs the PID frames due by `now`.
    fn advance(&mut self, now: Instant) {
        let due = (now.duration_since(self.start).as_secs_f64() * PID_RATE) as u64;
        while self.frames < due {
            self.frames += 1;
            let driven = self.moving || self.raw.is_some();
            if driven && now.duration_since(self.last_motor) > AUTO_STOP {
                self.moving = false;
                self.raw = None;
                self.target = (0, 0);
                self.speed = (0.0, 0.0);
                self.auto_stops += 1;
            }
            if let Some((l, r)) = self.raw {
                self.speed = (l, r);
            } else if self.moving {
                let (tl, tr) = (f64::from(self.target.0), f64::from(self.target.1));
                self.speed.0 += RESPONSE * (tl - self.speed.0);
                self.speed.1 += RESPONSE * (tr - self.speed.1);
            }
            self.left += self.speed.0;
            self.right += self.speed.1;
            for (angle, target) in self.servo_angle.iter_mut().zip(self.servo_target) {
                *angle += (target - *angle).clamp(-SERVO_STEP, SERVO_STEP);
            }
        }
    }

    /// The firmware's answer to one request line.
    fn answer(&mut self, line: &str, options: Options, now: Instant) -> String {
        let mut words = line.split(' ');
        let command = words.next().unwrap_or("");
        let arg1 = words.next().unwrap_or("");
        let arg2 = words.next().unwrap_or("");
        // Like atoi: anything unreadable is 0.
        let int = |s: &str| s.parse::<i64>().unwrap_or(0);
        match command {
            "e" => {
                let (l, r) = self.counts();
                format!("{l} {r}")
            }
            "m" => {
                self.last_motor = now;
                self.raw = None;
                self.target = (int(arg1) as i32, int(arg2) as i32);
                self.moving = self.target != (0, 0);
                if !self.moving {
                    self.speed = (0.0, 0.0);
                }
                "OK".into()
            }
            "o" => {
                self.last_motor = now;
                self.moving = false;
                let pwm = |s: &str| int(s).clamp(-255, 255) as f64 / 255.0 * FULL_PWM_TICKS;
                self.raw = Some((pwm(arg1), pwm(arg2)));
                "OK".into()
            }
            "r" => {
                self.left = 0.0;
                self.right = 0.0;
                "OK".into()
            }
            "u" if arg1.split(':').count() == 4 => "OK".into(),
            "b" => options.baud.to_string(),
            "s" | "t" if options.servos && (0..SERVOS as i64).contains(&int(arg1)) => {
                let i = int(arg1) as usize;
                if command == "s" {
                    self.servo_writes.push((i, int(arg2)));
                    // Servo.write clamps to 0..180.
                    self.servo_target[i] = int(arg2).clamp(0, 180) as f64;
                    "OK".into()
                } else {
                    format!("{}", self.servo_angle[i].round() as i64)
                }
            }
            _ => "Invalid Command".into(),
        }
    }
}

/// A `long` counter as the firmware holds it.
fn wrap(position: f64) -> i32 {
    position.floor() as i64 as i32
}

struct Shared {
    state: Mutex<State>,
    changed: Condvar,
}

// Unplug and Replug come from the fault switches (faults.rs), which only some tests use.
#[allow(dead_code)]
pub(super) enum Control {
    Unplug,
    Replug,
    Quit,
}

/// The firmware, running on its own thread until dropped.
pub struct Emulator {
    shared: Arc<Shared>,
    pub(super) control: Sender<Control>,
    thread: Option<JoinHandle<()>>,
    dir: PathBuf,
    link: PathBuf,
}

static NEXT: AtomicU32 = AtomicU32::new(0);

impl Emulator {
    pub fn start() -> Emulator {
        Self::start_with(Options::default())
    }

    pub fn start_with(options: Options) -> Emulator {
        let dir = std::env::temp_dir().join(format!(
            "navdeck-serial-{}-{}",
            std::process::id(),
            NEXT.fetch_add(1, Ordering::Relaxed)
        ));
        std::fs::create_dir_all(&dir).unwrap();
        let link = dir.join("ttyEMU0");
        let now = Instant::now();
        let shared = Arc::new(Shared {
            state: Mutex::new(State {
                requests: Vec::new(),
                left: 0.0,
                right: 0.0,
                target: (0, 0),
                moving: false,
                auto_stops: 0,
                servo_angle: [0.0; SERVOS],
                servo_writes: Vec::new(),
                plugged: true,
                frames: 0,
                raw: None,
                speed: (0.0, 0.0),
                servo_target: [0.0; SERVOS],
                last_motor: now,
                start: now,
                garbage: None,
                drop_next: false,
                delay_next: None,
                muted: false,
            }),
            changed: Condvar::new(),
        });
        let pty = Pty::open();
        std::os::unix::fs::symlink(&pty.slave_path, &link).unwrap();
        let (control, rx) = channel();
        let thread = {
            let shared = shared.clone();
            let link = link.clone();
            std::thread::spawn(move || serve(shared, rx, pty, link, options))
        };
        Emulator {
            shared,
            control,
            thread: Some(thread),
            dir,
            link,
        }
    }

    /// The device path to give navdeck.
    pub fn path(&self) -> String {
        self.link.to_string_lossy().into_owned()
    }

    pub fn state(&self) -> MutexGuard<'_, State> {
        self.shared.state.lock().unwrap()
    }

    /// Blocks until `done` holds (checked whenever the firmware does something), or fails
    /// the test after PATIENCE.
    pub fn wait_for(&self, what: &str, done: impl Fn(&State) -> bool) {
        let deadline = Instant::now() + PATIENCE;
        let mut state = self.state();
        while !done(&state) {
            let left = deadline.saturating_duration_since(Instant::now());
            assert!(
                !left.is_zero(),
                "the firmware never saw {what}; last requests: {:?}",
                state.requests.iter().rev().take(12).collect::<Vec<_>>()
            );
            state = self.shared.changed.wait_timeout(state, left).unwrap().0;
        }
    }
}

impl Drop for Emulator {
    fn drop(&mut self) {
        let _ = self.control.send(Control::Quit);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// Both sides of a pseudo-terminal; the slave side is kept open so the master never reads
/// a hang-up while navdeck reconnects.
struct Pty {
    master: OwnedFd,
    _slave: OwnedFd,
    slave_path: PathBuf,
}

impl Pty {
    fn open() -> Pty {
        let (mut master, mut slave) = (0, 0);
        // SAFETY: openpty writes two descriptors; null name, termios and size are allowed.
        let rc = unsafe {
            libc::openpty(
                &mut master,
                &mut slave,
                std::ptr::null_mut(),
                std::ptr::null(),
                std::ptr::null(),
            )
        };
        assert_eq!(rc, 0, "openpty: {}", std::io::Error::last_os_error());
        // SAFETY: both descriptors were just opened and are owned here alone.
        let (master, slave) =
            unsafe { (OwnedFd::from_raw_fd(master), OwnedFd::from_raw_fd(slave)) };
        let mut name = [0 as libc::c_char; 128];
        // SAFETY: the buffer is as long as we say.
        let rc = unsafe { libc::ttyname_r(slave.as_raw_fd(), name.as_mut_ptr(), name.len()) };
        assert_eq!(rc, 0, "ttyname_r");
        // SAFETY: ttyname_r wrote a NUL-terminated string into `name`.
        let path = unsafe { std::ffi::CStr::from_ptr(name.as_ptr()) };
        // Raw mode from the start, as the Arduino's UART has no line discipline.
        // SAFETY: termios is plain data, filled in by tcgetattr before use.
        unsafe {
            let mut t: libc::termios = std::mem::zeroed();
            libc::tcgetattr(slave.as_raw_fd(), &mut t);
            libc::cfmakeraw(&mut t);
            libc::tcsetattr(slave.as_raw_fd(), libc::TCSANOW, &t);
        }
        Pty {
            master,
            _slave: slave,
            slave_path: PathBuf::from(path.to_string_lossy().into_owned()),
        }
    }

    /// Waits up to `ms` for bytes from navdeck.
    fn read(&self, ms: i32) -> Vec<u8> {
        let mut fds = libc::pollfd {
            fd: self.master.as_raw_fd(),
            events: libc::POLLIN,
            revents: 0,
        };
        // SAFETY: one valid pollfd.
        let ready = unsafe { libc::poll(&mut fds, 1, ms) };
        if ready <= 0 || fds.revents & libc::POLLIN == 0 {
            return Vec::new();
        }
        let mut buf = [0u8; 512];
        // SAFETY: the buffer is as long as we say.
        let n = unsafe { libc::read(self.master.as_raw_fd(), buf.as_mut_ptr().cast(), buf.len()) };
        if n <= 0 {
            return Vec::new();
        }
        buf[..n as usize].to_vec()
    }

    fn write(&self, mut bytes: &[u8]) {
        while !bytes.is_empty() {
            // SAFETY: the slice is valid for its length.
            let n =
                unsafe { libc::write(self.master.as_raw_fd(), bytes.as_ptr().cast(), bytes.len()) };
            if n <= 0 {
                return;
            }
            bytes = &bytes[n as usize..];
        }
    }
}

/// The firmware's main loop.
fn serve(
    shared: Arc<Shared>,
    control: Receiver<Control>,
    pty: Pty,
    link: PathBuf,
    options: Options,
) {
    // Seconds one byte takes on the wire: start bit, 8 data bits, stop bit.
    let byte_time = 10.0 / f64::from(options.baud);
    let mut pty = Some(pty);
    let mut line = Vec::new();
    loop {
        match control.try_recv() {
            Ok(Control::Quit) | Err(std::sync::mpsc::TryRecvError::Disconnected) => return,
            Ok(Control::Unplug) => {
                pty = None;
                let _ = std::fs::remove_file(&link);
                line.clear();
                shared.state.lock().unwrap().plugged = false;
                shared.changed.notify_all();
            }
            Ok(Control::Replug) => {
                let fresh = Pty::open();
                let _ = std::fs::remove_file(&link);
                std::os::unix::fs::symlink(&fresh.slave_path, &link).unwrap();
                pty = Some(fresh);
                let mut s = shared.state.lock().unwrap();
                s.reset();
                s.plugged = true;
                drop(s);
                shared.changed.notify_all();
            }
            Err(std::sync::mpsc::TryRecvError::Empty) => {}
        }
        let bytes = match &pty {
            Some(port) => port.read(5),
            None => {
                std::thread::sleep(Duration::from_millis(5));
                Vec::new()
            }
        };
        let now = Instant::now();
        {
            let mut s = shared.state.lock().unwrap();
            let before = s.frames;
            s.advance(now);
            if s.frames != before {
                shared.changed.notify_all();
            }
        }
        for b in bytes {
            match b {
                b'\r' => {
                    let request = String::from_utf8_lossy(&line).into_owned();
                    line.clear();
                    let (reply, garbage, dropped, delay, muted) = {
                        let mut s = shared.state.lock().unwrap();
                        s.advance(Instant::now());
                        let reply = s.answer(&request, options, Instant::now());
                        s.requests.push(request.clone());
                        (
                            format!("{reply}\r\n"),
                            s.garbage.take(),
                            std::mem::take(&mut s.drop_next),
                            s.delay_next.take(),
                            s.muted,
                        )
                    };
                    shared.changed.notify_all();
                    // The request's bytes and the reply's take their time on the wire.
                    let wire = (request.len() + 1 + reply.len()) as f64 * byte_time;
                    std::thread::sleep(Duration::from_secs_f64(wire) + delay.unwrap_or_default());
                    let Some(port) = &pty else { continue };
                    if let Some(g) = garbage {
                        port.write(&g);
                    }
                    if !dropped && !options.silent && !muted {
                        port.write(reply.as_bytes());
                    }
                }
                b'\n' => {}
                _ if line.len() < 64 => line.push(b),
                _ => {}
            }
        }
    }
}
