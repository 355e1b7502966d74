//! Key press to cmd_vel on the wire, with the console's whole loop running (events,
//! control, drawing every change into a 120x40 test terminal) against the fake robot of
//! the ROS 2 tests on its own DDS participant. Prints the median and the 95th percentile.
//!
//! cargo bench --bench ros2_latency

#[path = "../tests/ros2_support/mod.rs"]
mod ros2_support;

use navdeck::app::{App, KeyKind, LinkStatus};
use navdeck::config::Config;
use navdeck::keymap::{Key, Keymap};
use navdeck::link::ros2::{Ros2Link, Ros2Options};
use navdeck::tui::events::{Clock, Event, EventSource, WallClock};
use navdeck::tui::run::{RunStats, run};
use navdeck::tui::theme::Theme;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use std::sync::atomic::AtomicUsize;
use std::sync::mpsc::{Receiver, RecvTimeoutError, channel};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// Presses measured by `cargo bench`; `cargo test` (no `--bench` argument) runs a
/// three-press smoke test of the same path.
const PRESSES: usize = 30;
const SMOKE_PRESSES: usize = 3;
const DOMAIN: u16 = 77;

/// Keys from another thread, each stamped when it was handed over.
struct Feed(Receiver<Event>);

impl EventSource for Feed {
    fn next_event(&mut self, timeout: Duration) -> std::io::Result<Option<Event>> {
        match self.0.recv_timeout(timeout) {
            Ok(e) => Ok(Some(e)),
            Err(RecvTimeoutError::Timeout) => Ok(None),
            Err(RecvTimeoutError::Disconnected) => Ok(Some(Event::Closed)),
        }
    }
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

fn main() {
    let presses = if std::env::args().any(|a| a == "--bench") {
        PRESSES
    } else {
        SMOKE_PRESSES
    };
    let robot = ros2_support::FakeRobot::start(ros2_support::FakeOptions::new(DOMAIN));
    let mut config = Config::default();
    config.ros2.interfaces = vec!["127.0.0.1".into()];
    let link = Ros2Link::connect(Ros2Options {
        config: config.ros2.clone(),
        domain: DOMAIN,
        track: config.robot.track,
        max_wheel_speed: config.robot.max_wheel_speed(),
    })
    .expect("ROS 2 link");
    let clock = WallClock::start();
    let mut app = App::new(config, Keymap::default_map(), Box::new(link), clock.now());
    // Wait for the robot before the first key.
    let give_up = Instant::now() + Duration::from_secs(20);
    while app.pilot().link_status() != &LinkStatus::Ok || app.now() < 1.5 {
        assert!(Instant::now() < give_up, "the fake robot never answered");
        app.update(clock.now());
        std::thread::sleep(Duration::from_millis(5));
    }
    let (tx, rx) = channel();
    let pressed = Arc::new(Mutex::new(Vec::new()));
    let stamps = pressed.clone();
    let feeder = std::thread::spawn(move || {
        for _ in 0..presses {
            // Long enough for the deadman to stop the robot and the zeros to go out.
            std::thread::sleep(Duration::from_millis(1200));
            stamps.lock().unwrap().push(Instant::now());
            tx.send(Event::Key(Key::char('w'), KeyKind::Press)).unwrap();
        }
        std::thread::sleep(Duration::from_millis(300));
    });
    let mut terminal = Terminal::new(TestBackend::new(120, 40)).unwrap();
    let mut stats = RunStats::default();
    let signal = AtomicUsize::new(0);
    run(
        &mut terminal,
        &mut app,
        &mut Feed(rx),
        &clock,
        &signal,
        Theme::from_env(None),
        &mut stats,
    )
    .unwrap();
    feeder.join().unwrap();
    let seen = robot.seen();
    let mut latencies: Vec<f64> = pressed
        .lock()
        .unwrap()
        .iter()
        .filter_map(|&at| {
            seen.cmd_vel
                .iter()
                .find(|(when, v, _)| *when >= at && *v > 0.0)
                .map(|(when, _, _)| (*when - at).as_secs_f64() * 1000.0)
        })
        .collect();
    latencies.sort_by(f64::total_cmp);
    assert_eq!(latencies.len(), presses, "every press reached the robot");
    println!(
        "key press to cmd_vel received: {} of {presses} presses, median {:.2} ms, p95 {:.2} ms, max {:.2} ms ({} frames drawn)",
        latencies.len(),
        percentile(&latencies, 0.5),
        percentile(&latencies, 0.95),
        latencies.last().unwrap(),
        stats.frames_drawn
    );
}
