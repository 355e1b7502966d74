//! The console's part in a fleet: what it asks of the fleet (select another robot, stop
//! them all) and the other robots it draws on its map.

use super::App;
use super::log::Level;
use crate::geometry::Pose2;

/// What a key or a typed command asks of the fleet around this console.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum FleetAsk {
    /// Select the next robot (`+1`) or the one before (`-1`).
    Step(i8),
    /// `:robot NAME`: select the robot of that name (or number, from 1).
    Select(String),
    /// Stop every robot.
    StopAll,
    /// `:robot add NS`: the robot under a ROS 2 namespace joins.
    Add(String),
}

/// Another robot of the fleet as this console draws it: its number from 1, its name and
/// where it believes it is.
#[derive(Clone, Debug, PartialEq)]
pub struct FleetMark {
    pub number: usize,
    pub name: String,
    pub pose: Pose2,
}

/// The fleet's asks waiting to be taken, and the other robots to draw.
#[derive(Clone, Debug, Default)]
pub(super) struct FleetView {
    ask: Option<FleetAsk>,
    marks: Vec<FleetMark>,
}

impl App {
    /// Leaves `ask` for the fleet to take; a console on its own stops its one robot for
    /// a stop-all, and says there is no other robot to select.
    pub(super) fn ask_fleet(&mut self, ask: FleetAsk) {
        self.fleet.ask = Some(ask);
    }

    /// What the console asked of its fleet since the last call.
    pub fn take_fleet_ask(&mut self) -> Option<FleetAsk> {
        self.fleet.ask.take()
    }

    /// The other robots of the fleet, drawn on this console's map.
    pub fn set_fleet_marks(&mut self, marks: Vec<FleetMark>) {
        if marks != self.fleet.marks {
            self.fleet.marks = marks;
            self.refresh_revision();
        }
    }

    /// This robot is number `number` of a fleet whose other robots stand as `peers`, in
    /// its own map frame: it gives way to them when it drives itself.
    pub fn set_fleet(&mut self, number: usize, peers: Vec<crate::control::fleet_yield::Peer>) {
        self.runtime.pilot_mut().set_fleet(number, peers);
    }

    /// The blocks the fleet's other robots claim and those they delivered, for this
    /// robot's mission.
    pub fn share_work(&mut self, taken: std::collections::BTreeSet<u32>, elsewhere: &[u32]) {
        self.runtime.pilot_mut().share_work(taken, elsewhere);
    }

    /// The exploration goals the fleet's other robots claim, what they explored and where
    /// they stand, for this robot's mission.
    pub fn share_exploration(&mut self, share: crate::mission::shared::FleetShare) {
        self.runtime.pilot_mut().share_exploration(share);
    }

    pub fn fleet_marks(&self) -> &[FleetMark] {
        &self.fleet.marks
    }

    /// A line from the fleet into this console's log (selection, stop-all, a lost link).
    pub fn note(&mut self, level: Level, text: impl Into<String>) {
        self.log(level, text);
        self.refresh_revision();
    }
}
