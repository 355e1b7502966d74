//! The work a fleet's twins share, passed between them before each one steps: the
//! blocks each claims and those delivered (`mission::claims`), the exploration goal each
//! claims (`mission::frontier_claims`) and what each explored. Twins of one world share
//! its frame; robots on real links each have their own odometry frame, which navdeck
//! does not yet join into one map, so they share nothing.

use super::Fleet;
use crate::mission::fleet_explored::ExploredLayer;
use crate::mission::frontier_claims::FrontierClaims;
use crate::mission::shared::FleetShare;
use std::sync::Arc;

impl Fleet {
    /// Which robots are twins (and so share work).
    fn twins(&self) -> Vec<bool> {
        (self.members.iter())
            .map(|m| m.app.link().ground_truth().is_some())
            .collect()
    }

    /// Tells twin `i`'s mission the blocks the fleet's other twins claim and those they
    /// delivered; its own claim is settled first come, first served.
    pub(super) fn share_work(&mut self, i: usize) {
        let twins = self.twins();
        if !twins[i] {
            return;
        }
        let wants: Vec<Option<u32>> = (self.members.iter().zip(&twins))
            .map(|(m, &twin)| m.app.pilot().fleet_claim().filter(|_| twin))
            .collect();
        self.claims.settle(&wants);
        let taken = self.claims.taken_for(i);
        let elsewhere: Vec<u32> = (self.members.iter().enumerate())
            .filter(|(k, _)| *k != i && twins[*k])
            .flat_map(|(_, m)| m.app.pilot().delivered_ids())
            .collect();
        self.members[i].app.share_work(taken, &elsewhere);
    }

    /// What each twin explored, once a tick (none for a robot on a real link, or a fleet
    /// with fewer than two twins).
    pub(super) fn explored_layers(&self) -> Vec<Option<Arc<ExploredLayer>>> {
        let twins = self.twins();
        let sharing = twins.iter().filter(|t| **t).count() > 1;
        (self.members.iter().zip(twins))
            .map(|(m, twin)| match twin && sharing {
                true => m.app.pilot().explored_layer().map(Arc::new),
                false => None,
            })
            .collect()
    }

    /// Tells twin `i`'s mission the exploration goals the other twins claim, with the
    /// ground round each (the camera's view range: what the claimant looks at from
    /// there), what they explored and where they stand; its own goal is settled first
    /// come, first served.
    pub(super) fn share_exploration(&mut self, i: usize, explored: &[Option<Arc<ExploredLayer>>]) {
        let twins = self.twins();
        if !twins[i] {
            return;
        }
        let reach = self.members[i].app.config().mission.view_range;
        if self.frontiers.reach() != reach {
            self.frontiers = FrontierClaims::new(reach);
        }
        let wants: Vec<Option<_>> = (self.members.iter().zip(&twins))
            .map(|(m, &twin)| m.app.pilot().fleet_frontier().filter(|_| twin))
            .collect();
        self.frontiers.settle(&wants);
        let taken = self.frontiers.taken_for(i);
        let others: Vec<Arc<ExploredLayer>> = (explored.iter().enumerate())
            .filter(|(k, _)| *k != i)
            .filter_map(|(_, layer)| layer.clone())
            .collect();
        let peers = (self.members.iter().enumerate())
            .filter(|(k, _)| *k != i && twins[*k])
            .map(|(_, m)| m.app.pilot().estimated_pose().position())
            .collect();
        self.members[i].app.share_exploration(FleetShare {
            taken,
            reach,
            others,
            peers,
        });
    }
}
