//! A link that records what it was asked, for checking the console's side of the contract.

use navdeck::app::App;
use navdeck::config::Config;
use navdeck::data::{Command, SensorFrame};
use navdeck::keymap::Keymap;
use navdeck::link::{LinkError, RobotLink};
use std::sync::{Arc, Mutex};

/// A link that records the commands it was sent and how often it was stopped.
#[derive(Clone, Default)]
pub struct RecordingLink {
    pub sent: Arc<Mutex<Vec<Command>>>,
    pub stops: Arc<Mutex<usize>>,
}

impl RobotLink for RecordingLink {
    fn label(&self) -> String {
        "recording".into()
    }
    fn send(&mut self, command: &Command) -> Result<(), LinkError> {
        self.sent.lock().unwrap().push(*command);
        Ok(())
    }
    fn poll(&mut self, now: f64) -> Result<SensorFrame, LinkError> {
        Ok(SensorFrame {
            stamp: now,
            ..SensorFrame::default()
        })
    }
    fn stop(&mut self) {
        *self.stops.lock().unwrap() += 1;
    }
}

/// A console on a recording link with the default keymap.
pub fn recording_app() -> (App, RecordingLink) {
    let link = RecordingLink::default();
    let app = App::new(
        Config::default(),
        Keymap::default_map(),
        Box::new(link.clone()),
        0.0,
    );
    (app, link)
}
