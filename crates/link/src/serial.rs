//! A robot running the ROSArduinoBridge firmware on a serial port (the protocol
//! diffdrive_arduino and ros_arduino_bridge speak), behind the link trait.
//!
//! The blocking port I/O runs as a worker in the links' runtime's pool for blocking work
//! (`tasks`); `send` hands it the latest command and `poll` collects the wheel travel it
//! read; its warnings and a lost or found port wake the console. Fault totals (retries, timeouts,
//! garbage lines, replies out of turn, `Invalid Command`s, rejected encoder jumps,
//! reconnects) are kept in `stats()` and summarised as notes for the console's log.

pub mod arm;
pub mod config;
pub mod open;
pub mod protocol;
pub mod transport;
pub mod wheels;
pub mod worker;

use super::{Command, GripperState, LinkError, Notice, RobotLink, SensorFrame, WheelTravel};
use arm::ArmServos;
use config::SerialConfig;
use navdeck_core::data::ArmTarget;
use navdeck_core::data::robot::RobotConfig;
use std::sync::Arc;
use std::sync::mpsc::{self, Receiver, Sender};
use tokio::task::JoinHandle;
use transport::Counters;
pub use transport::SerialStats;
use wheels::WheelGeometry;
use worker::{FromWorker, Settings, ToWorker, Worker};

/// Why the link could not be set up.
#[derive(Debug, thiserror::Error)]
pub enum ConnectError {
    #[error("`{0}` is not PATH[@BAUD]: {1}")]
    Spec(String, &'static str),
    #[error("cannot connect to {path} at {baud} baud: {reason}")]
    Port {
        path: String,
        baud: u32,
        reason: String,
    },
}

/// Splits `PATH[@BAUD]`; the baud defaults to `default_baud`.
pub fn parse_spec(spec: &str, default_baud: u32) -> Result<(String, u32), ConnectError> {
    let bad = |why| ConnectError::Spec(spec.to_string(), why);
    let (path, baud) = match spec.rsplit_once('@') {
        Some((path, baud)) => {
            let baud = baud
                .parse::<u32>()
                .ok()
                .filter(|b| *b > 0)
                .ok_or_else(|| bad("the baud rate after @ must be a positive whole number"))?;
            (path, baud)
        }
        None => (spec, default_baud),
    };
    if path.is_empty() {
        return Err(bad("the device path is empty"));
    }
    Ok((path.to_string(), baud))
}

/// A ROSArduinoBridge robot on a serial port.
pub struct SerialLink {
    label: String,
    to_worker: Sender<ToWorker>,
    from_worker: Receiver<FromWorker>,
    worker: Option<JoinHandle<()>>,
    counters: Arc<Counters>,
    lost: Option<String>,
    travel: WheelTravel,
    elapsed: f64,
    gripper: Option<GripperState>,
    /// The arm's servos, and the newest target (sent again after a reconnection).
    arm: ArmServos,
    arm_target: Option<ArmTarget>,
    warned_no_arm: bool,
    notes: Vec<Notice>,
}

impl SerialLink {
    /// Opens `PATH[@BAUD]` for `robot` and waits for the firmware to answer.
    pub fn open(
        spec: &str,
        serial: &SerialConfig,
        robot: &RobotConfig,
    ) -> Result<SerialLink, ConnectError> {
        let (path, baud) = parse_spec(spec, serial.baud)?;
        let settings = Settings {
            path: path.clone(),
            baud,
            serial: serial.clone(),
            geometry: WheelGeometry {
                wheel_radius: robot.wheel_radius,
                track: robot.track,
                counts_per_rev: serial.counts_per_rev,
                pid_rate_hz: serial.pid_rate_hz,
            },
            max_wheel_speed: robot.max_wheel_speed(),
        };
        let counters = Arc::new(Counters::default());
        let transport =
            worker::open(&settings, &counters).map_err(|reason| ConnectError::Port {
                path: path.clone(),
                baud,
                reason,
            })?;
        let (to_worker, rx) = mpsc::channel();
        let (tx, from_worker) = mpsc::channel();
        let worker = Worker::new(settings, rx, tx, counters.clone());
        let handle = crate::tasks::spawn_blocking(move || worker.run(transport)).map_err(|e| {
            ConnectError::Port {
                path: path.clone(),
                baud,
                reason: e.to_string(),
            }
        })?;
        Ok(SerialLink {
            label: format!("serial:{path}@{baud}"),
            to_worker,
            from_worker,
            worker: Some(handle),
            counters,
            lost: None,
            travel: WheelTravel::default(),
            elapsed: 0.0,
            gripper: None,
            arm: ArmServos::new(&serial.arm_servos),
            arm_target: None,
            warned_no_arm: false,
            notes: Vec::new(),
        })
    }

    /// The fault and traffic totals so far.
    pub fn stats(&self) -> SerialStats {
        self.counters.snapshot()
    }

    fn drain(&mut self) {
        while let Ok(message) = self.from_worker.try_recv() {
            match message {
                FromWorker::Travel { wheels, elapsed } => {
                    self.travel.left += wheels.left;
                    self.travel.right += wheels.right;
                    self.elapsed += elapsed;
                }
                FromWorker::Gripper(g) => self.gripper = Some(g),
                FromWorker::Connected => {
                    self.lost = None;
                    self.notes.push(Notice::warn("serial: reconnected"));
                    // A board that reset holds its servos where it starts them.
                    self.arm.forget();
                    if let Some(target) = self.arm_target {
                        let _ = self.order_arm(target);
                    }
                }
                FromWorker::Lost(reason) => self.lost = Some(reason),
                FromWorker::Note(note) => self.notes.push(Notice::warn(note)),
            }
        }
    }

    /// The servo writes for an arm target, when it moved; clamped angles are noted.
    fn order_arm(&mut self, target: ArmTarget) -> Result<(), LinkError> {
        if !self.arm.configured() {
            if !std::mem::replace(&mut self.warned_no_arm, true) {
                self.notes.push(Notice::warn(
                    "serial: arm target ignored: no [serial] arm_servos configured",
                ));
            }
            return Ok(());
        }
        self.arm_target = Some(target);
        let plan = self.arm.plan(&target);
        let warnings = plan.warnings.into_iter();
        self.notes
            .extend(warnings.map(|w| Notice::warn(format!("serial: {w}"))));
        if plan.writes.is_empty() {
            return Ok(());
        }
        self.order(ToWorker::Servos(plan.writes))
    }

    fn order(&self, message: ToWorker) -> Result<(), LinkError> {
        self.to_worker
            .send(message)
            .map_err(|_| LinkError::Lost(format!("{}: the port's worker stopped", self.label)))
    }
}

impl RobotLink for SerialLink {
    fn label(&self) -> String {
        self.label.clone()
    }

    fn send(&mut self, command: &Command) -> Result<(), LinkError> {
        self.drain();
        if let Some(reason) = &self.lost {
            return Err(LinkError::Lost(reason.clone()));
        }
        self.order(ToWorker::Drive(command.twist))?;
        if let Some(g) = command.gripper {
            self.order(ToWorker::Gripper(g))?;
        }
        if let Some(target) = command.arm {
            self.order_arm(target)?;
        }
        Ok(())
    }

    fn poll(&mut self, now: f64) -> Result<SensorFrame, LinkError> {
        self.drain();
        if let Some(reason) = &self.lost {
            // Travel read before the loss stays for the next good poll.
            return Err(LinkError::Lost(reason.clone()));
        }
        let moved = self.elapsed > 0.0;
        let frame = SensorFrame {
            stamp: now,
            elapsed: std::mem::take(&mut self.elapsed),
            wheels: moved.then(|| std::mem::take(&mut self.travel)),
            sightings: None,
            scan: None,
            gripper: self.gripper,
            camera: None,
            initial_pose: None,
            goal: None,
            arm: None,
            lane: None,
            tags: None,
        };
        Ok(frame)
    }

    fn stop(&mut self) {
        // Best effort: if the worker is gone, so is the port, and the firmware's 2 s
        // auto-stop is the last line.
        let _ = self.to_worker.send(ToWorker::Stop);
    }

    fn take_notes(&mut self) -> Vec<Notice> {
        self.drain();
        std::mem::take(&mut self.notes)
    }
}

impl Drop for SerialLink {
    /// Stops the motors (`m 0 0`) and closes the port before the link goes.
    fn drop(&mut self) {
        let _ = self.to_worker.send(ToWorker::Shutdown);
        if let Some(handle) = self.worker.take() {
            crate::tasks::join(handle);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn specs_split_into_path_and_baud() {
        assert_eq!(
            parse_spec("/dev/ttyACM0", 57600).unwrap(),
            ("/dev/ttyACM0".to_string(), 57600)
        );
        assert_eq!(
            parse_spec("/dev/ttyUSB1@115200", 57600).unwrap(),
            ("/dev/ttyUSB1".to_string(), 115200)
        );
        for bad in ["/dev/ttyACM0@fast", "/dev/ttyACM0@0", "@57600"] {
            let e = parse_spec(bad, 57600).unwrap_err().to_string();
            assert!(e.contains(bad), "{e}");
        }
    }

    #[test]
    fn a_missing_device_is_a_clear_error() {
        let e = SerialLink::open(
            "/nonexistent/ttyACM9",
            &SerialConfig::default(),
            &RobotConfig::default(),
        )
        .err()
        .expect("no such device")
        .to_string();
        assert!(
            e.contains("/nonexistent/ttyACM9") && e.contains("57600"),
            "{e}"
        );
    }
}
