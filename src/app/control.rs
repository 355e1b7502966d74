//! The console's side of the control loop: it hands time and intents to the robot's
//! runtime (`link::runtime`), which runs the schedule, the pilot and the link, and takes
//! what each step brought into its log, panels and map files.

use super::App;
use super::mode::Mode;
use crate::link::runtime::{Event, Stepped};
use crate::pilot;

impl App {
    /// Runs every control step due up to `now` (periodic ticks and deadman expiries),
    /// then takes in what the robot reported since.
    pub fn update(&mut self, now: f64) {
        self.record_input(crate::msgs::record::InputMsg::update(now));
        self.advance_to(now);
        // Between control steps, still bring what the robot reports up to date.
        let sensed = self.runtime.sense(now);
        self.absorb(sensed);
        self.poll_picker(false);
        self.pass_log();
        self.refresh_revision();
    }

    /// Seconds of session time until the console next needs to run, for the event wait.
    pub fn next_deadline(&self) -> f64 {
        self.runtime.next_deadline()
    }

    pub(super) fn advance_to(&mut self, now: f64) {
        let intents = self.localising_intents();
        let stepped = self.runtime.tick(now, intents);
        self.absorb(stepped);
    }

    /// Hands `intent` to the pilot in one step; a command follows at once when it changed
    /// the motion. Anything but a speed change takes over from the localising move.
    pub(super) fn run_intent(&mut self, intent: pilot::Intent) {
        if !matches!(intent, pilot::Intent::Speed(_)) {
            self.end_localising("taken over");
        }
        let stepped = self.runtime.intend(intent);
        self.absorb(stepped);
    }

    /// Takes what the steps brought, in order: log lines, mode changes, what the camera
    /// and the markers showed, and the autosave of each exploration tick.
    pub(super) fn absorb(&mut self, stepped: Stepped) {
        // The newest loop closure's line: flashed when it comes in.
        let closed = (self.pilot().lidar_slam())
            .and_then(|s| s.closures.last())
            .map(pilot::lidar_slam::closure_line);
        for event in stepped.events {
            match event {
                Event::Log {
                    time,
                    level,
                    text,
                    source,
                } => {
                    let notable = source.is_none() && closed.as_ref() == Some(&text);
                    self.log.push_from(time, level, source, text);
                    if notable {
                        self.log.flash_newest();
                    }
                }
                Event::Mode { before, .. } => self.follow_mode(before),
                Event::Frame { time, frame } => {
                    if let Some(s) = &frame.sightings {
                        self.note_sightings(time, s);
                    }
                    if let Some(status) = frame.camera {
                        self.note_camera(time, status);
                    }
                }
                Event::Sent { .. } => {}
                Event::Tick { time, mode } => {
                    if mode == Mode::Exploration {
                        self.autosave(time);
                    }
                }
            }
        }
    }

    /// Keeps the console's mode-dependent state (goal cursor, map picker) in step with the
    /// pilot's mode, which was `before`.
    fn follow_mode(&mut self, before: Mode) {
        let mode = self.pilot().mode();
        if mode != before {
            self.cursor = (mode == Mode::Thinking).then(|| self.pilot().cursor_start());
            if mode == Mode::Load {
                self.open_picker();
            }
        }
    }
}
