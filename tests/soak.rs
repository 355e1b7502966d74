//! Eight simulated hours of the console on the twin, run headless through the real main
//! loop and renderer: each hour drives by keys, runs the mission, plans and follows a
//! path, saves the map and idles. Resident memory is sampled every simulated hour and
//! must stay flat, the log bounded, and the session clock, the twin's clock and the
//! control loop's rate must agree at the end (no drift).
//!
//! Alone in its file: resident memory is the process's, and no other test may share it.

use crate::common;

use common::{hold, key, press};
use navdeck::keymap::{Key, KeyCode};
use navdeck::tui::events::{Clock, Event, EventSource, ManualClock, ScriptedEvents, Step};
use navdeck::tui::run::Exit;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use std::io;
use std::time::{Duration, Instant};

const HOUR: f64 = 3600.0;
const HOURS: usize = 8;
/// Growth of resident memory allowed from the end of hour 2 to the end of hour 8: room
/// for the allocator's noise, far below what a leak of a few bytes a tick would add
/// (8 h at 10 Hz is 288,000 ticks).
const FLAT: u64 = 8 << 20;

/// Resident memory of this process, bytes.
fn resident_bytes() -> u64 {
    let statm = std::fs::read_to_string("/proc/self/statm").expect("/proc/self/statm");
    let pages: u64 = statm
        .split_whitespace()
        .nth(1)
        .and_then(|p| p.parse().ok())
        .expect("resident pages");
    // SAFETY: sysconf with a valid name.
    let page = unsafe { libc::sysconf(libc::_SC_PAGESIZE) } as u64;
    pages * page
}

/// The script, sampling resident memory each time simulated time passes an hour.
struct Sampled {
    script: ScriptedEvents,
    clock: ManualClock,
    samples: Vec<u64>,
}

impl EventSource for Sampled {
    fn next_event(&mut self, timeout: Duration) -> io::Result<Option<Event>> {
        let event = self.script.next_event(timeout);
        while self.clock.now() >= (self.samples.len() + 1) as f64 * HOUR - 1e-6 {
            self.samples.push(resident_bytes());
        }
        event
    }
}

fn typed(text: &str) -> Vec<Step> {
    let mut steps: Vec<Step> = text.chars().map(press).collect();
    steps.push(Step::Event(Event::Key(
        Key::new(KeyCode::Enter),
        navdeck::app::KeyKind::Press,
    )));
    steps
}

/// One hour of use; `h` varies the goal so each hour plans a different path.
fn one_hour(h: usize) -> Vec<Step> {
    let mut steps = Vec::new();
    let mut used = 0.0;
    let wait = |steps: &mut Vec<Step>, s: f64| {
        steps.push(Step::Wait(s));
        s
    };
    // Driving by keys, as a held key auto-repeats.
    for (c, s) in [('w', 3.0), ('a', 1.0), ('w', 2.0), ('d', 1.5), ('s', 1.0)] {
        steps.extend(hold(c, s));
        used += s;
    }
    used += wait(&mut steps, 5.0);
    // The mission for a quarter of an hour, then control taken back with the e-stop.
    steps.push(press('e'));
    used += wait(&mut steps, 900.0);
    steps.push(Step::Event(Event::Key(
        key("space"),
        navdeck::app::KeyKind::Press,
    )));
    used += wait(&mut steps, 2.0);
    steps.extend(hold('w', 1.0));
    used += 1.0;
    used += wait(&mut steps, 3.0);
    // Plan and follow a path to a point that changes every hour.
    let goal = [(0.5, 0.5), (-0.5, 0.8), (0.8, -0.6), (-0.7, -0.7)][h % 4];
    steps.extend(typed(&format!(":goto {} {}", goal.0, goal.1)));
    used += wait(&mut steps, 120.0);
    steps.push(press('m'));
    // Save the map.
    steps.push(press('S'));
    used += wait(&mut steps, 10.0);
    // Idle for the rest of the hour.
    wait(&mut steps, HOUR - used);
    steps
}

#[test]
fn eight_hours_on_the_twin_keep_memory_log_and_clock_steady() {
    let maps = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("soak-maps");
    let _ = std::fs::remove_dir_all(&maps);
    let mut app = common::default_app();
    app.set_maps_dir(maps.clone());
    let clock = ManualClock::default();
    let steps: Vec<Step> = (0..HOURS).flat_map(one_hour).collect();
    let mut events = Sampled {
        script: ScriptedEvents::new(clock.clone(), steps),
        clock: clock.clone(),
        samples: Vec::new(),
    };
    let mut terminal = Terminal::new(TestBackend::new(100, 30)).unwrap();
    let started = Instant::now();
    let (exit, stats) = common::run_loop(&mut terminal, &mut app, &mut events, &clock);
    let exit = exit.expect("the loop runs");
    let wall = started.elapsed();
    assert_eq!(exit, Exit::InputClosed);

    let mib: Vec<String> = (events.samples.iter())
        .map(|b| format!("{:.1}", *b as f64 / (1 << 20) as f64))
        .collect();
    eprintln!(
        "soak: {HOURS} simulated hours in {:.1} s wall; {} frames drawn; resident MiB by hour: {}",
        wall.as_secs_f64(),
        stats.frames_drawn,
        mib.join(" ")
    );
    assert_eq!(events.samples.len(), HOURS, "one sample an hour");
    let growth = events.samples[HOURS - 1].saturating_sub(events.samples[1]);
    assert!(
        growth < FLAT,
        "resident memory grew {growth} bytes from hour 2 to hour {HOURS}: {mib:?}"
    );

    // The log keeps a bounded tail however much was written.
    let log = app.log_book();
    assert!(log.written() > 100, "a busy session logs");
    assert!(
        log.iter().count() < 1000,
        "{} lines kept",
        log.iter().count()
    );

    // No drift: the session, the twin and the control loop agree after 8 hours.
    let end = HOURS as f64 * HOUR;
    assert!(
        (app.now() - end).abs() < 1e-6,
        "session clock {}",
        app.now()
    );
    let twin_time = app.link().ground_truth().expect("the twin").time();
    let period = app.config().robot.control_period;
    assert!(
        (twin_time - end).abs() <= period,
        "the twin's clock {twin_time} s against {end} s"
    );
    assert!(
        (app.loop_rate() - 1.0 / period).abs() < 0.01 / period,
        "control loop at {} Hz",
        app.loop_rate()
    );
    let overruns = log.iter().filter(|e| e.text.contains("overran")).count();
    assert_eq!(overruns, 0, "the loop fell behind on simulated time");

    // The last hour planned its path and saved its map, as the first did.
    let last_hour = |text: &str| {
        log.iter()
            .any(|e| e.time > end - HOUR && e.text.contains(text))
    };
    assert!(last_hour("path to (-0.70, -0.70)"), "no path planned");
    assert!(last_hour("saved.yaml"), "no map saved");
    assert!(maps.join("saved.yaml").exists());
}
