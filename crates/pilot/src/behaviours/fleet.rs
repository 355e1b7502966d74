//! Fleet yield: a robot of a fleet, driving itself, gives way to another as
//! `control::fleet_yield` rules, holding still (it may still turn) until the other has
//! passed. The fleet around the pilot tells it its number and where the others stand.

use super::{Behaviour, Proposal};
use crate::Pilot;
use navdeck_core::control::fleet_yield::{Peer, Right, YieldRule, judge, narrow_at};
use navdeck_core::geometry::{Point2, Twist};
use navdeck_core::map::costmap::is_lethal;
use navdeck_core::mission::fleet_explored::ExploredLayer;
use navdeck_core::mission::shared::FleetShare;

/// Cells within this of a robot's centre are that robot, not a wall, metres (a
/// TurtleBot3's 0.105 m half-width and a cell).
const ROBOT_REACH: f64 = 0.15;

/// This robot's number in its fleet and the others as last told.
#[derive(Clone, Debug, Default)]
pub(crate) struct FleetWatch {
    number: usize,
    peers: Vec<Peer>,
    rule: YieldRule,
}

/// The task behaviours a robot drives itself by: they give way. Keys never do.
fn drives_itself(b: Behaviour) -> bool {
    matches!(
        b,
        Behaviour::PathFollowing
            | Behaviour::TagRoute
            | Behaviour::PickAndPlace
            | Behaviour::Exploration
            | Behaviour::LaneFollowing
    )
}

impl Pilot {
    /// This robot is number `number` (from 1) of a fleet whose other robots stand as
    /// `peers`; told again every control period while they move.
    pub fn set_fleet(&mut self, number: usize, peers: Vec<Peer>) {
        let robot = &self.settings.robot;
        self.behaviours.fleet = FleetWatch {
            number,
            peers,
            rule: YieldRule::for_robot(robot.control_period, robot.max_linear_accel),
        };
    }

    /// The hold `task` owes another robot of the fleet, if it owes one.
    pub(super) fn yield_proposal(&self, task: &Proposal) -> Option<Proposal> {
        let fleet = &self.behaviours.fleet;
        if fleet.peers.is_empty() || !drives_itself(task.behaviour) {
            return None;
        }
        let me = self.estimated_pose();
        let costmap = self.belief.costmap();
        let robots: Vec<Point2> = (fleet.peers.iter().map(|p| p.pose.position()))
            .chain(std::iter::once(me.position()))
            .collect();
        let wall = |q: Point2| {
            is_lethal(costmap.at(q)) && robots.iter().all(|r| r.distance(q) > ROBOT_REACH)
        };
        let rule = &fleet.rule;
        let narrow = |p: Point2| narrow_at(p, rule.doorway, costmap.resolution, &wall);
        let linear = task.twist.linear;
        match judge(rule, fleet.number, me, linear, &fleet.peers, &narrow) {
            Right::Go => None,
            Right::Yield { to, why } => Some(Proposal::new(
                Behaviour::FleetYield,
                Twist::new(0.0, task.twist.angular),
                format!("giving way to robot {to}: {why}"),
            )),
        }
    }
}

impl Pilot {
    /// The block this robot's mission works on (its odd marker), for the fleet's claims.
    pub fn fleet_claim(&self) -> Option<u32> {
        self.exploring.mission.as_ref().and_then(|m| m.claim())
    }

    /// The blocks this robot's mission delivered, by odd marker.
    pub fn delivered_ids(&self) -> Vec<u32> {
        (self.exploring.mission.as_ref()).map_or_else(Vec::new, |m| m.delivered_ids())
    }

    /// The blocks the fleet's other robots claim and those they delivered, for this
    /// robot's mission (`Mission::share`).
    pub fn share_work(&mut self, taken: std::collections::BTreeSet<u32>, elsewhere: &[u32]) {
        if let Some(m) = self.exploring.mission.as_mut() {
            m.share(taken, elsewhere);
        }
    }
}

impl Pilot {
    /// The exploration goal this robot's mission drives to, for the fleet's frontier
    /// claims: none unless it is exploring, so a robot that stops or leaves exploration
    /// lets its claim go.
    pub fn fleet_frontier(&self) -> Option<Point2> {
        if self.mode() != crate::mode::Mode::Exploration {
            return None;
        }
        self.exploring.mission.as_ref()?.frontier_claim()
    }

    /// What this robot has explored (its map's mapped cells, what its camera looked at),
    /// for the fleet's other robots; none before its mission started.
    pub fn explored_layer(&self) -> Option<ExploredLayer> {
        let mission = self.exploring.mission.as_ref()?;
        Some(mission.explored_layer(self.belief.costmap()))
    }

    /// The exploration goals the fleet's other robots claim, what they explored and where
    /// they stand, for this robot's mission (`Mission::share_exploration`).
    pub fn share_exploration(&mut self, share: FleetShare) {
        if let Some(m) = self.exploring.mission.as_mut() {
            m.share_exploration(share);
        }
    }
}
