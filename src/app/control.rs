//! The control loop's schedule: a control step every period (seed 001: 0.1 s) and at
//! each deadman expiry; each step polls the link, runs the pilot and sends its command.

use super::App;
use super::log::Level;
use super::mode::Mode;
use crate::pilot::{self, Due};

/// A stall longer than this is skipped rather than caught up, seconds.
const MAX_CATCH_UP: f64 = 1.0;
/// Seconds within which a control step counts as due.
const TICK_SLACK: f64 = 1e-9;
/// At most one overrun warning per this many seconds.
const WARN_EVERY: f64 = 5.0;

/// When the next control step is due, and how regularly steps have run.
#[derive(Clone, Debug)]
pub(super) struct ControlClock {
    period: f64,
    next_tick: f64,
    last_update: f64,
    rate: f64,
    last_warning: f64,
}

impl ControlClock {
    pub(super) fn new(now: f64, period: f64) -> Self {
        Self {
            period,
            next_tick: now,
            last_update: now,
            rate: 1.0 / period,
            last_warning: f64::NEG_INFINITY,
        }
    }

    /// Control steps completed per second, smoothed.
    pub(super) fn rate(&self) -> f64 {
        self.rate
    }
}

impl App {
    /// Runs every control step due up to `now` (periodic ticks and deadman expiries).
    pub fn update(&mut self, now: f64) {
        self.record_input(crate::msgs::record::InputMsg::update(now));
        self.advance_to(now);
        // Between control steps, still bring what the robot reports up to date.
        self.sense(now);
        self.poll_picker(false);
        self.pass_log();
        self.refresh_revision();
    }

    /// Seconds of session time until the console next needs to run, for the event wait.
    pub fn next_deadline(&self) -> f64 {
        let tick = self.clock.next_tick;
        self.pilot
            .teleop_cutoff(self.now)
            .map_or(tick, |c| c.min(tick))
    }

    pub(super) fn advance_to(&mut self, now: f64) {
        if now < self.now {
            return;
        }
        let gap = now - self.clock.last_update;
        if gap > 1.5 * self.clock.period && self.clock.next_tick <= now {
            if now - self.clock.last_warning >= WARN_EVERY {
                self.clock.last_warning = now;
                self.log.push(
                    now,
                    Level::Warn,
                    format!(
                        "Warning! dt = {gap:.2} s: control loop overran its {:.2} s period",
                        self.clock.period
                    ),
                );
            }
            if now - self.clock.next_tick > MAX_CATCH_UP {
                self.clock.next_tick = now;
            }
        }
        loop {
            let tick = self.clock.next_tick;
            let due = self
                .pilot
                .teleop_cutoff(self.now)
                .map_or(tick, |c| c.min(tick));
            // A tick due a rounding error after `now` is due now: sums of 0.1 s drift apart.
            if due > now + TICK_SLACK {
                break;
            }
            if due >= tick {
                self.clock.next_tick = tick + self.clock.period;
                let dt = due - self.clock.last_update;
                if dt > 0.0 {
                    // Exponential smoothing over about ten ticks.
                    self.clock.rate += 0.1 * (1.0 / dt - self.clock.rate);
                }
                self.clock.last_update = due;
                self.run_step(due, Due::Tick);
                self.show_picture(due);
                self.record_tick(due);
                if self.pilot.mode() == Mode::Exploration {
                    self.autosave(due);
                }
            } else {
                self.run_step(due, Due::Command);
            }
        }
        self.now = now;
    }

    /// One sense-decide-act cycle at session time `t`.
    pub(super) fn control_step(&mut self, t: f64) {
        self.run_step(t, Due::Command);
    }

    /// Collects what the robot reported up to `t`, without deciding anything.
    pub(super) fn sense(&mut self, t: f64) {
        self.run_step(t, Due::Nothing);
    }

    /// Polls the link at `t`, runs the pilot on what it reported, and sends the command
    /// when one is due; then the console's own panels take what the frame showed.
    fn run_step(&mut self, t: f64, due: Due) {
        self.now = self.now.max(t);
        let before = self.pilot.mode();
        let mut stepped = crate::link::drive::step(self.link.as_mut(), &mut self.pilot, t, due);
        self.record_step(t, &stepped);
        self.take_log(std::mem::take(&mut stepped.log));
        self.follow_mode(before);
        if let Some(frame) = stepped.frame {
            if let Some(s) = &frame.sightings {
                self.note_sightings(t, s);
            }
            if let Some(status) = frame.camera {
                self.note_camera(t, status);
            }
            self.note_collisions(t);
        }
        for note in self.link.take_notes() {
            self.log.push_from(t, note.level, note.source, note.text);
        }
    }

    /// Runs the pilot on `input` alone (no link), logs what it said.
    pub(super) fn pilot_step(&mut self, input: pilot::Input<'_>) -> pilot::Output {
        let before = self.pilot.mode();
        let mut out = self.pilot.step(input);
        let log = std::mem::take(&mut out.log);
        self.take_log(log);
        self.follow_mode(before);
        out
    }

    fn take_log(&mut self, lines: Vec<pilot::LogLine>) {
        for line in lines {
            self.log.push(line.time, line.level, line.text);
        }
    }

    /// Keeps the console's mode-dependent state (goal cursor, map picker) in step with the
    /// pilot's mode, which was `before`.
    fn follow_mode(&mut self, before: Mode) {
        let mode = self.pilot.mode();
        if mode != before {
            self.cursor = (mode == Mode::Thinking).then(|| self.pilot.cursor_start());
            if mode == Mode::Load {
                self.open_picker();
            }
        }
    }

    /// The twin counts contacts; each new one is worth a line in the log.
    fn note_collisions(&mut self, t: f64) {
        let Some(truth) = self.link.ground_truth() else {
            return;
        };
        if let Some(note) = crate::sim::collision_note(truth, &mut self.collisions_logged) {
            self.log.push(t, Level::Warn, note);
        }
    }
}
