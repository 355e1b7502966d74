//! The twin behind the link trait: the default robot when no hardware is at hand.

use super::{Command, LinkError, Notice, RobotLink, SensorFrame};
use navdeck_core::sim::{Faults, Twin};

/// Drives the digital twin; `poll(now)` steps its physics up to `now`.
pub struct SimLink {
    twin: Twin,
    clock: f64,
}

impl SimLink {
    /// A link whose session clock starts at `start` seconds.
    pub fn new(twin: Twin, start: f64) -> Self {
        Self { twin, clock: start }
    }
}

impl RobotLink for SimLink {
    fn label(&self) -> String {
        format!("sim:{}", self.twin.world().name)
    }

    fn send(&mut self, command: &Command) -> Result<(), LinkError> {
        self.twin.set_command(command.twist);
        if let Some(g) = command.gripper {
            self.twin.command_gripper(g);
        }
        if let Some(target) = &command.arm {
            self.twin.command_arm(target);
        }
        Ok(())
    }

    fn poll(&mut self, now: f64) -> Result<SensorFrame, LinkError> {
        if now > self.clock {
            self.twin.step(now - self.clock);
            self.clock = now;
        }
        Ok(self.twin.take_frame())
    }

    fn stop(&mut self) {
        self.twin.set_command(navdeck_core::geometry::Twist::ZERO);
    }

    fn teleport(&mut self, pose: navdeck_core::geometry::Pose2) -> bool {
        self.twin.teleport(pose);
        true
    }
    fn ground_truth(&self) -> Option<&dyn navdeck_core::sim::GroundTruth> {
        Some(&self.twin)
    }

    fn faults(&self) -> Option<&Faults> {
        Some(self.twin.faults())
    }

    fn faults_mut(&mut self) -> Option<&mut Faults> {
        Some(self.twin.faults_mut())
    }

    /// Each injected fault as it begins (a warning) and ends.
    fn take_notes(&mut self) -> Vec<Notice> {
        let notes = self.twin.faults_mut().take_notes();
        (notes.into_iter())
            .map(|n| {
                if n.began {
                    Notice::warn(n.text)
                } else {
                    Notice::info(n.text)
                }
            })
            .collect()
    }
}
