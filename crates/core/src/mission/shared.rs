//! One robot's mission in a fleet's shared work: the block it claims, the blocks the
//! other robots claim (left to them), and those they delivered (forgotten here); the
//! exploration goal it claims, the goals the others claim (their ground left to them),
//! and what the others explored (taken as explored here).

use super::Mission;
use super::fleet_explored::ExploredLayer;
use super::frontier_claims::is_free;
use super::phase::{Phase, Target};
use crate::geometry::Point2;
use crate::map::costmap::Costmap;
use std::collections::BTreeSet;
use std::sync::Arc;

/// What the fleet passes one robot's mission each step about its exploration.
#[derive(Clone, Debug, Default)]
pub struct FleetShare {
    /// The exploration goals the other robots claim.
    pub taken: Vec<Point2>,
    /// The ground each claimed goal keeps round it, metres.
    pub reach: f64,
    /// What the other robots explored.
    pub others: Vec<Arc<ExploredLayer>>,
    /// Where the other robots stand.
    pub peers: Vec<Point2>,
}

/// What the fleet's other robots share with one robot's mission.
#[derive(Clone, Debug, Default)]
pub(super) struct Shared {
    /// Blocks the others claim (odd markers): never chosen here.
    pub blocks: BTreeSet<u32>,
    /// Exploration goals the others claim and what they explored: the fleet's last word.
    pub fleet: FleetShare,
    /// The last choice left out an exploration target because another robot claims it.
    pub claimed_out: bool,
    /// Waiting for the others' claimed ground (said once in the log).
    pub waiting: bool,
    /// Since when (mission time) the mission has had nothing to do but another robot
    /// stands at the edge of the space it can reach (`fleet_wait.rs`).
    pub boxed_since: Option<f64>,
    /// Where the mission started, and whether it went back there (or could not) once it
    /// had nothing left in a fleet (`fleet_wait.rs`).
    pub home: Option<Point2>,
    pub home_reached: bool,
}

impl Shared {
    /// The targets among `found` outside the ground the others claim; notes whether any
    /// was left out.
    pub fn unclaimed(&mut self, found: Vec<Point2>) -> Vec<Point2> {
        let before = found.len();
        let free: Vec<Point2> = (found.into_iter())
            .filter(|p| is_free(*p, &self.fleet.taken, self.fleet.reach))
            .collect();
        self.claimed_out |= free.len() < before;
        free
    }
}

impl Mission {
    /// The block this mission works on (its odd marker): the one it picks up or carries.
    pub fn claim(&self) -> Option<u32> {
        self.block_being_picked().or(self.held)
    }

    /// The blocks this mission delivered, by odd marker.
    pub fn delivered_ids(&self) -> Vec<u32> {
        self.delivered_blocks().map(|b| b.markers[0]).collect()
    }

    /// The blocks the fleet's other robots claim (`taken`: never chosen here), and those
    /// they delivered (`elsewhere`: forgotten, and their markers ignored from now on).
    pub fn share(&mut self, taken: BTreeSet<u32>, elsewhere: &[u32]) {
        self.shared.blocks = taken;
        for &odd in elsewhere {
            if !self.delivered_markers.contains(&odd) {
                self.delivered_markers.extend([odd, odd + 1]);
                self.objects.forget(odd);
            }
        }
    }

    /// The exploration goal this mission drives to (a frontier or unseen space), for the
    /// fleet's claims; none while it does anything else.
    pub fn frontier_claim(&self) -> Option<Point2> {
        match &self.phase {
            Phase::Explore {
                leg,
                target: Target::Frontier | Target::Unseen,
            } => Some(leg.goal),
            _ => None,
        }
    }

    /// Whether this mission has done exploring: ended, or with nothing left going back
    /// to where it started (`fleet_wait.rs`).
    pub fn done_exploring(&self) -> bool {
        matches!(
            self.phase,
            Phase::Done
                | Phase::Manual
                | Phase::Explore {
                    target: Target::Home,
                    ..
                }
        )
    }

    /// What this robot explored, for the fleet's other robots: `map` is its planning map.
    pub fn explored_layer(&self, map: &Costmap) -> ExploredLayer {
        ExploredLayer::new(map, &self.explored.coverage)
    }

    /// The exploration goals the fleet's other robots claim (each keeping its ground),
    /// what they explored and where they stand. A goal of this mission's own that now
    /// lies in claimed ground is dropped and another chosen.
    pub fn share_exploration(&mut self, share: FleetShare) {
        let own = self.frontier_claim();
        if own.is_some_and(|g| !is_free(g, &share.taken, share.reach)) {
            self.phase = Phase::Choose;
        }
        self.shared.fleet = share;
    }

    /// What the fleet's other robots explored, as this mission takes it: nothing while
    /// it explores alone.
    pub(super) fn explored_elsewhere(&self) -> Vec<Arc<ExploredLayer>> {
        match self.explores_alone() {
            true => Vec::new(),
            false => self.shared.fleet.others.clone(),
        }
    }

    /// A mission that knows a block it cannot deliver because it has not seen that
    /// colour's gate explores on its own map alone: the others' share does not say where
    /// the gate is, only that they have been there.
    fn explores_alone(&self) -> bool {
        let gateless = |colour| self.objects.gate_for(colour).is_none();
        (self.objects.blocks())
            .filter(|b| !b.delivered && !self.shared.blocks.contains(&b.markers[0]))
            .filter(|b| b.confirmed || self.held == Some(b.markers[0]))
            .any(|b| gateless(b.colour))
    }
}

#[cfg(test)]
mod tests;
