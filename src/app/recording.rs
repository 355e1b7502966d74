//! Recording the session (`--record`, `[record]`): what the console was told and what it
//! logged, beside what the robot's runtime records of each step and tick
//! (`link::runtime::recording`). `navdeck replay` reads it back.

use super::App;
use super::log::Level;
use crate::link::ConsoleLine;
use crate::link::ros2::{NODE_NAME, rosout};
use crate::link::runtime::TickEstimate;
use crate::link::runtime::recording::Recording;
use crate::msgs::record::{InputMsg, LogMsg, TruthMsg};
use crate::record::{Recorder, Summary, Topic};
use std::collections::BTreeMap;

impl App {
    /// Records the session from now on into `recorder`: the config and the twin's world
    /// as attachments, `session` (how it was started) as metadata.
    pub fn record_to(&mut self, mut recorder: Recorder, mut session: BTreeMap<String, String>) {
        let config = toml::to_string(&self.config).unwrap_or_default();
        let mut blocks = Vec::new();
        let now = self.now();
        recorder.attach("config.toml", "application/toml", config.into_bytes());
        if let Some(truth) = self.link().ground_truth() {
            recorder.attach(
                "world.toml",
                "application/toml",
                truth.world().to_toml().into_bytes(),
            );
            let first = TruthMsg::of(now, truth);
            blocks = first.blocks.clone();
            recorder.publish(Topic::Truth, now, first);
        }
        session.insert("navdeck".into(), env!("CARGO_PKG_VERSION").into());
        session.insert("link".into(), self.link().label());
        session.insert("start_time".into(), format!("{now}"));
        recorder.metadata("navdeck", session);
        let (width, height) = self.screen;
        let resize = InputMsg::resize(now, width, height);
        recorder.publish(Topic::Input, now, resize);
        // Lines not yet passed to the link go to it alone; the recording takes the whole
        // book so far, then every new line with the link.
        self.pass_log();
        let earlier = self.log.expanded();
        self.log.keep_fresh();
        let (robot, record) = (self.config.robot.clone(), self.config.record.clone());
        let shared_map = self.link().ground_truth().is_some();
        let recording = Recording::new(recorder, robot, record, (blocks, now), shared_map);
        self.runtime.record_into(recording);
        self.record_lines(earlier);
        self.pass_log();
    }

    /// Where the session is being recorded, if it is.
    pub fn recording_path(&self) -> Option<&std::path::Path> {
        self.runtime.recording().map(|r| r.path())
    }

    /// The recording in progress, for the header's mark: its size on disk so far, bytes,
    /// and how long it has run, seconds.
    pub fn recording_progress(&self) -> Option<(u64, f64)> {
        let r = self.runtime.recording()?;
        Some((r.bytes_written(), self.now() - r.started()))
    }

    /// Waits until the recording's writer has written everything so far (benchmarks).
    pub fn wait_for_recording(&mut self) {
        if let Some(r) = self.runtime.recording_mut() {
            r.recorder().wait_for_writer();
        }
    }

    /// Closes the recording and says what it holds.
    pub fn finish_recording(&mut self) -> Option<Result<Summary, String>> {
        self.pass_log();
        let recording = self.runtime.take_recording()?;
        Some(recording.into_recorder().finish())
    }

    /// One call into the console, so a replay can make it again.
    pub(super) fn record_input(&mut self, msg: InputMsg) {
        if let Some(r) = self.runtime.recording_mut() {
            let t = msg.time;
            r.recorder().publish(Topic::Input, t, msg);
        }
    }

    /// The log lines written since the last call, to the link that passes them on
    /// (/rosout) and into the recording as /rosout carries them.
    pub(super) fn pass_log(&mut self) {
        let takes_log = self.link().takes_log();
        if self.runtime.recording().is_none() && !takes_log {
            return;
        }
        let fresh = self.log.take_fresh();
        if takes_log && !fresh.is_empty() {
            let lines: Vec<ConsoleLine> = fresh
                .iter()
                .map(|e| ConsoleLine {
                    level: e.level,
                    text: e.text.clone(),
                    source: e.source.clone(),
                })
                .collect();
            self.runtime.link_mut().log(&lines);
        }
        self.record_lines(fresh);
    }

    fn record_lines(&mut self, lines: Vec<super::log::Entry>) {
        let now = self.now();
        let Some(r) = self.runtime.recording_mut() else {
            return;
        };
        let recorder = r.recorder();
        if let Some(why) = recorder.take_problem() {
            self.log.push(now, Level::Warn, why);
        }
        for e in lines {
            let msg = LogMsg {
                stamp: recorder.stamp(e.time),
                level: rosout::severity(e.level),
                name: e.source.unwrap_or_else(|| NODE_NAME.into()),
                msg: e.text,
                ..LogMsg::default()
            };
            recorder.publish(Topic::Log, e.time, msg);
        }
        recorder.hand_over_due(now);
    }

    /// From now on each control tick's estimate is kept for `take_tick_estimates`.
    pub fn watch_estimates(&mut self) {
        self.runtime.watch_estimates();
    }

    /// The estimates of the control ticks since the last call (with `watch_estimates`).
    pub fn take_tick_estimates(&mut self) -> Vec<TickEstimate> {
        self.runtime.take_tick_estimates()
    }
}
