//! A console on a robot link a test switches on and off.

use navdeck::app::App;
use navdeck::link::{Command, LinkError, RobotLink, SensorFrame};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// A link called `label` that answers while its flag is set and otherwise reports the
/// loss `lost`.
struct SwitchedLink {
    label: &'static str,
    lost: &'static str,
    alive: Arc<AtomicBool>,
}

impl RobotLink for SwitchedLink {
    fn label(&self) -> String {
        self.label.into()
    }
    fn send(&mut self, _: &Command) -> Result<(), LinkError> {
        Ok(())
    }
    fn poll(&mut self, now: f64) -> Result<SensorFrame, LinkError> {
        if self.alive.load(Ordering::SeqCst) {
            Ok(SensorFrame {
                stamp: now,
                ..Default::default()
            })
        } else {
            Err(LinkError::Lost(self.lost.into()))
        }
    }
    fn stop(&mut self) {}
}

/// The default console on a link called `label`, answering from the start when `up`,
/// and the flag that switches it.
pub fn switched_app(label: &'static str, lost: &'static str, up: bool) -> (App, Arc<AtomicBool>) {
    let alive = Arc::new(AtomicBool::new(up));
    let link = SwitchedLink {
        label,
        lost,
        alive: alive.clone(),
    };
    let app = App::new(
        navdeck::config::Config::default(),
        navdeck::keymap::Keymap::default_map(),
        Box::new(link),
        0.0,
    );
    (app, alive)
}
