//! The twin behind the link trait: the default robot when no hardware is at hand.

use super::{Command, LinkError, Notice, RobotLink, SensorFrame};
use navdeck_core::sim::fleet::FleetBoard;
use navdeck_core::sim::{Faults, Twin};
use std::sync::{Arc, Mutex};

/// The board a fleet's twins share, and this robot's place on it.
type Seat = (Arc<Mutex<FleetBoard>>, usize);

/// Drives the digital twin; `poll(now)` steps its physics up to `now`.
pub struct SimLink {
    twin: Twin,
    clock: f64,
    /// In a fleet: the board through which the robots see each other and share blocks.
    fleet: Option<Seat>,
}

impl SimLink {
    /// A link whose session clock starts at `start` seconds.
    pub fn new(twin: Twin, start: f64) -> Self {
        Self {
            twin,
            clock: start,
            fleet: None,
        }
    }

    /// Robot `index` of a fleet whose twins share `board`: before each step it takes the
    /// others' poses and the blocks from the board, after it writes its own back.
    pub fn in_fleet(twin: Twin, start: f64, board: Arc<Mutex<FleetBoard>>, index: usize) -> Self {
        Self {
            fleet: Some((board, index)),
            ..Self::new(twin, start)
        }
    }

    fn step(&mut self, dt: f64) {
        let Some((board, me)) = &self.fleet else {
            self.twin.step(dt);
            return;
        };
        // A robot that panicked while holding the board left it as it was: still usable.
        let mut board = board.lock().unwrap_or_else(|e| e.into_inner());
        board.before_step(*me, &mut self.twin);
        self.twin.step(dt);
        board.after_step(*me, &self.twin);
    }
}

impl RobotLink for SimLink {
    fn label(&self) -> String {
        match &self.fleet {
            Some((_, me)) => format!("sim:{} #{}", self.twin.world().name, me + 1),
            None => format!("sim:{}", self.twin.world().name),
        }
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
            self.step(now - self.clock);
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
