//! One robot's runtime: its link, its pilot, the control schedule, the recording and the
//! twin's contact notes, behind one `tick(now, intents)`. The console, `--headless`,
//! `navdeck mission`, `navdeck tour` and `navdeck replay` all drive a robot through it;
//! a fleet is a `Vec` of runtimes. Time comes in from the caller: nothing here reads a
//! clock.

pub mod frames;
pub mod localising;
mod picture;
pub mod recording;
mod schedule;
pub mod state;
mod tag_graph;

use crate::{Notice, RobotLink};
use navdeck_core::data::frame_check::FrameChecker;
use navdeck_core::data::{Command, Level, SensorFrame};
use navdeck_core::geometry::Pose2;
use navdeck_pilot::config::Settings;
use navdeck_pilot::mode::Mode;
use navdeck_pilot::{Due, Input, Intent, Pilot, Robot};
use recording::Recording;
use schedule::{Next, Schedule, TICK_SLACK};

/// The planning map reaches this far beyond a simulated world's walls, metres: a lidar hit
/// on a wall at the map's very edge lands outside half the time, and the beam then clears
/// the edge cells instead of mapping the wall there.
const MAP_MARGIN: f64 = 0.25;

/// The estimate at one control tick: session time, pose, covariance.
pub type TickEstimate = (f64, Pose2, nalgebra::Matrix3<f64>);

/// What happened in one call, in order, for the caller's own panels, log and files.
#[derive(Debug, Default)]
pub struct Stepped {
    pub events: Vec<Event>,
}

/// One thing a step brought.
#[derive(Debug)]
pub enum Event {
    /// A line for the log: the pilot's, the twin's contact notes, the link's own (with
    /// the robot's node that said it, when one did).
    Log {
        time: f64,
        level: Level,
        text: String,
        source: Option<String>,
    },
    /// The pilot changed mode at `time`; it was `before`.
    Mode { time: f64, before: Mode },
    /// What one poll of the robot brought at `time`.
    Frame { time: f64, frame: Box<SensorFrame> },
    /// A command went to the robot at `time` (sent, or tried and failed: the log says).
    Sent { time: f64, command: Command },
    /// A periodic control step ran at `time`, in `mode`.
    Tick { time: f64, mode: Mode },
}

/// One robot's link, pilot and schedule; see the module comment.
pub struct Runtime {
    link: Box<dyn RobotLink>,
    pilot: Pilot,
    schedule: Schedule,
    now: f64,
    /// Twin contacts already logged.
    collisions_logged: u32,
    /// What was last shown to a link that shows navdeck's picture (RViz over ROS 2).
    shown: picture::Shown,
    recording: Option<Recording>,
    /// Each control tick's estimate, kept for a replay to compare (`watch_estimates`).
    watched: Option<Vec<TickEstimate>>,
    /// The one check every frame passes, with its tally of what it refused.
    checker: FrameChecker,
    /// A session time refused already (named once).
    bad_time_named: bool,
}

/// Session times beyond this are refused, seconds (about 32 years): a control period
/// still adds to them exactly enough (f64 resolves 1e-7 s there), so catching up ends.
pub const MAX_SESSION_TIME: f64 = 1e9;

/// The link as the pilot's step sees it: every frame passes the one frame check on its
/// way in, whichever link brought it, and what the check took out is logged.
struct Port<'a> {
    link: &'a mut dyn RobotLink,
    checker: &'a mut FrameChecker,
    refusals: &'a mut Vec<(f64, String)>,
}

impl Robot for Port<'_> {
    fn poll(&mut self, t: f64) -> Result<SensorFrame, String> {
        match self.link.poll(t) {
            Ok(frame) => {
                let (kept, lines) = self.checker.check(t, frame);
                self.refusals.extend(lines.into_iter().map(|l| (t, l)));
                Ok(kept.unwrap_or(SensorFrame {
                    stamp: t,
                    ..SensorFrame::default()
                }))
            }
            Err(e) => {
                let why = e.to_string();
                Err(if why.trim().is_empty() {
                    "the link failed without saying why".to_string()
                } else {
                    why
                })
            }
        }
    }
    fn truth(&self) -> Option<Pose2> {
        self.link.ground_truth().map(|g| g.pose())
    }
    fn send(&mut self, command: &Command) -> Result<(), String> {
        self.link.send(command).map_err(|e| e.to_string())
    }
}

impl Runtime {
    /// A runtime for the robot behind `link` from session time `now`, its first control
    /// step due at once. With a simulator behind the link the pilot starts at the true
    /// pose and its planning map covers the simulated world when that is larger than the
    /// config's; otherwise it starts at the origin.
    pub fn new(link: Box<dyn RobotLink>, settings: Settings, now: f64) -> Self {
        let truth = link.ground_truth();
        let start = truth.map_or(Pose2::default(), |t| t.pose());
        let m = 2.0 * MAP_MARGIN;
        let extent = truth.map_or((0.0, 0.0), |t| (t.world().width + m, t.world().height + m));
        let period = settings.robot.control_period;
        let checker = FrameChecker::new(settings.robot.max_wheel_speed());
        Self {
            pilot: Pilot::new(settings, start, extent, now),
            link,
            schedule: Schedule::new(now, period),
            now,
            collisions_logged: 0,
            shown: picture::Shown::default(),
            recording: None,
            watched: None,
            checker,
            bad_time_named: false,
        }
    }

    /// Runs every control step due up to `now` (the periodic ticks and the deadman's
    /// expiries). `intents` ride in the step due at `now` when there is one; otherwise
    /// each rides in a step of its own, which polls and commands the robot at once when
    /// it changed the motion.
    pub fn tick(&mut self, now: f64, intents: Vec<Intent>) -> Stepped {
        let mut stepped = Stepped::default();
        if !self.time_usable(now, &mut stepped) || now < self.now {
            return stepped;
        }
        if let Some(text) = self.schedule.overrun(now) {
            stepped.log(now, Level::Warn, text);
        }
        let mut intents = intents.into_iter();
        loop {
            let cutoff = self.pilot.teleop_cutoff(self.now);
            let Some(next) = self.schedule.take_due(now, cutoff) else {
                break;
            };
            let (time, due) = match next {
                Next::Tick(t) => (t, Due::Tick),
                Next::Command(t) => (t, Due::Command),
            };
            // The step due at `now` carries what was asked at `now`.
            let asked = if time >= now - TICK_SLACK {
                intents.by_ref().collect()
            } else {
                Vec::new()
            };
            self.run(time, asked, due, &mut stepped);
            if due == Due::Tick {
                self.after_tick(time, &mut stepped);
            }
        }
        for intent in intents {
            self.ask(intent, &mut stepped);
        }
        self.now = now;
        stepped
    }

    /// One step at the runtime's time for `intent`: it polls and commands the robot at
    /// once when it changed the motion (a key, a goal, a mode).
    pub fn intend(&mut self, intent: Intent) -> Stepped {
        let mut stepped = Stepped::default();
        self.ask(intent, &mut stepped);
        stepped
    }

    fn ask(&mut self, intent: Intent, stepped: &mut Stepped) {
        self.run(self.now, vec![intent], Due::IfActing, stepped);
    }

    /// Polls the robot at `now` and folds in what it reported, deciding nothing: what a
    /// robot reports between control steps is taken in as it comes.
    pub fn sense(&mut self, now: f64) -> Stepped {
        let mut stepped = Stepped::default();
        if self.time_usable(now, &mut stepped) {
            self.run(now, Vec::new(), Due::Sense, &mut stepped);
        }
        stepped
    }

    /// Whether `now` is a session time the schedule can run to: finite and below
    /// `MAX_SESSION_TIME`. The first one that is not is named.
    fn time_usable(&mut self, now: f64, stepped: &mut Stepped) -> bool {
        if now.is_finite() && now.abs() <= MAX_SESSION_TIME {
            return true;
        }
        if !std::mem::replace(&mut self.bad_time_named, true) {
            let text = format!(
                "session time {} s refused: it must be finite, within ±{} s",
                navdeck_core::data::frame_check::short(now),
                navdeck_core::data::frame_check::short(MAX_SESSION_TIME)
            );
            stepped.log(self.now, Level::Warn, text);
        }
        false
    }

    /// One step of the pilot at `t` with `intents`, and what it brought.
    fn run(&mut self, t: f64, intents: Vec<Intent>, due: Due, stepped: &mut Stepped) {
        self.now = self.now.max(t);
        let before = self.pilot.mode();
        let mut intents = intents;
        let last = intents.pop();
        let mut log = Vec::new();
        let mut refusals = Vec::new();
        let mut port = Port {
            link: self.link.as_mut(),
            checker: &mut self.checker,
            refusals: &mut refusals,
        };
        // Every intent but the last is applied alone; the last rides with the step.
        for intent in intents {
            let input = Input::apply(t, intent);
            log.extend(self.pilot.step(input, &mut port).log);
        }
        let input = Input {
            t,
            intent: last,
            due,
        };
        let mut out = self.pilot.step(input, &mut port);
        for (time, text) in refusals {
            stepped.log(time, Level::Warn, text);
        }
        log.append(&mut out.log);
        let polled = out.frame.is_some() || out.failure.is_some();
        if polled && let Some(r) = self.recording.as_mut() {
            r.step(t, &out, self.link.ground_truth());
        }
        for line in log {
            stepped.log(line.time, line.level, line.text);
        }
        if self.pilot.mode() != before {
            stepped.events.push(Event::Mode { time: t, before });
        }
        if let Some(command) = out.command {
            stepped.events.push(Event::Sent { time: t, command });
        }
        if !polled {
            return;
        }
        if let Some(frame) = out.frame {
            let frame = Box::new(frame);
            stepped.events.push(Event::Frame { time: t, frame });
            let truth = self.link.ground_truth();
            let note = truth
                .and_then(|g| navdeck_core::sim::collision_note(g, &mut self.collisions_logged));
            if let Some(text) = note {
                stepped.log(t, Level::Warn, text);
            }
        }
        for Notice {
            level,
            text,
            source,
        } in self.link.take_notes()
        {
            let time = t;
            stepped.events.push(Event::Log {
                time,
                level,
                text,
                source,
            });
        }
    }

    /// What follows each periodic step: the picture to a link that shows it, the
    /// recording's and the replay's estimate.
    fn after_tick(&mut self, t: f64, stepped: &mut Stepped) {
        self.show_picture(t);
        let pilot = &self.pilot;
        if let Some(watched) = self.watched.as_mut() {
            watched.push((t, pilot.estimated_pose(), pilot.pose_covariance()));
        }
        if let Some(r) = self.recording.as_mut() {
            r.tick(t, pilot);
        }
        let mode = pilot.mode();
        stepped.events.push(Event::Tick { time: t, mode });
    }

    /// Session seconds until the runtime next needs to run: the next control step or
    /// the deadman's expiry.
    pub fn next_deadline(&self) -> f64 {
        self.schedule.next_due(self.pilot.teleop_cutoff(self.now))
    }

    /// Tells the robot to stop now, outside a control step (quit, signal, lost input).
    pub fn stop(&mut self) {
        self.link.stop();
        let t = self.now;
        if let Some(r) = self.recording.as_mut() {
            r.command(t, &Command::STOP);
        }
    }

    /// Control steps completed per second, smoothed.
    pub fn loop_rate(&self) -> f64 {
        self.schedule.rate()
    }
    pub fn now(&self) -> f64 {
        self.now
    }
    pub fn pilot(&self) -> &Pilot {
        &self.pilot
    }
    /// The pilot, to set it up before it runs (MCL, the planning stopwatch).
    pub fn pilot_mut(&mut self) -> &mut Pilot {
        &mut self.pilot
    }
    pub fn link(&self) -> &dyn RobotLink {
        self.link.as_ref()
    }
    pub fn link_mut(&mut self) -> &mut dyn RobotLink {
        self.link.as_mut()
    }
    /// The faults injected into the twin, and which are in force now (`Faults::active`,
    /// `Faults::is_active`); None where no twin stands behind the link.
    pub fn faults(&self) -> Option<&navdeck_core::sim::Faults> {
        self.link.faults()
    }

    /// Records what each step polls and sends and what each tick believes, from now on.
    pub fn record_into(&mut self, recording: Recording) {
        self.recording = Some(recording);
    }
    /// The recording in progress, for the caller's own topics.
    pub fn recording_mut(&mut self) -> Option<&mut Recording> {
        self.recording.as_mut()
    }
    pub fn recording(&self) -> Option<&Recording> {
        self.recording.as_ref()
    }
    /// Ends the recording, handing back its recorder to be finished.
    pub fn take_recording(&mut self) -> Option<Recording> {
        self.recording.take()
    }

    /// From now on each control tick's estimate is kept for `take_tick_estimates`.
    pub fn watch_estimates(&mut self) {
        self.watched = Some(Vec::new());
    }
    /// The estimates of the control ticks since the last call (with `watch_estimates`).
    pub fn take_tick_estimates(&mut self) -> Vec<TickEstimate> {
        self.watched
            .as_mut()
            .map(std::mem::take)
            .unwrap_or_default()
    }
}

impl Stepped {
    fn log(&mut self, time: f64, level: Level, text: String) {
        let source = None;
        self.events.push(Event::Log {
            time,
            level,
            text,
            source,
        });
    }

    /// The log lines, in order, with their times ("time level text" for runners).
    pub fn log_lines(&self) -> impl Iterator<Item = (f64, Level, &str)> {
        self.events.iter().filter_map(|e| match e {
            Event::Log {
                time, level, text, ..
            } => Some((*time, *level, text.as_str())),
            _ => None,
        })
    }
}
