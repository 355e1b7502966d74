//! Route mode's tag camera beside a real robot's link (seed 003 §1.2.2): the link drives
//! and senses as before, and the tag pipeline's newest reading rides along in each frame
//! as the twin's tag camera's sightings do. Why frames go unread (no camera_info yet, a
//! calibration refused, a frame of another size) reaches the log once, when it changes.

use super::{Command, ConsoleLine, LinkError, Notice, Picture, RobotLink, SensorFrame};
use navdeck_core::perception::tag_pipeline::{TagPipeline, TagReading};

pub struct WithTagCamera {
    inner: Box<dyn RobotLink>,
    pipeline: TagPipeline,
    source: String,
    /// Why frames went unread, as last logged; None while they are read.
    unread: Option<String>,
    /// Whether a frame was read yet (its first reading is logged).
    reading: bool,
    notes: Vec<Notice>,
}

impl WithTagCamera {
    pub fn new(inner: Box<dyn RobotLink>, pipeline: TagPipeline, source: String) -> Self {
        Self {
            inner,
            pipeline,
            source,
            unread: None,
            reading: false,
            notes: Vec::new(),
        }
    }

    /// The newest reading as the frame's tags, and what changed as a log line.
    fn take_reading(&mut self, frame: &mut SensorFrame) {
        match self.pipeline.take_latest() {
            Some(TagReading::Seen(seen)) => {
                if !self.reading || self.unread.is_some() {
                    let line = format!("tag camera {}: reading tags", self.source);
                    self.notes.push(Notice::info(line));
                }
                self.reading = true;
                self.unread = None;
                frame.tags = Some(seen.detections.iter().map(|d| d.sighting).collect());
            }
            Some(TagReading::Unread(why)) if self.unread.as_ref() != Some(&why) => {
                let line = format!("tag camera {}: {why}", self.source);
                self.notes.push(Notice::warn(line));
                self.unread = Some(why);
            }
            Some(TagReading::Unread(_)) => {}
            None => {}
        }
    }
}

impl RobotLink for WithTagCamera {
    fn label(&self) -> String {
        format!("{} + tag camera {}", self.inner.label(), self.source)
    }

    fn send(&mut self, command: &Command) -> Result<(), LinkError> {
        self.inner.send(command)
    }

    fn poll(&mut self, now: f64) -> Result<SensorFrame, LinkError> {
        let mut frame = self.inner.poll(now)?;
        self.take_reading(&mut frame);
        Ok(frame)
    }

    fn stop(&mut self) {
        self.inner.stop();
    }

    fn picture_period(&self) -> Option<f64> {
        self.inner.picture_period()
    }

    fn show(&mut self, picture: &Picture) {
        self.inner.show(picture);
    }

    fn take_notes(&mut self) -> Vec<Notice> {
        let mut notes = self.inner.take_notes();
        notes.append(&mut self.notes);
        notes
    }

    fn details(&self, now: f64) -> Vec<(&'static str, String)> {
        self.inner.details(now)
    }

    fn takes_log(&self) -> bool {
        self.inner.takes_log()
    }

    fn log(&mut self, lines: &[ConsoleLine]) {
        self.inner.log(lines);
    }
}
