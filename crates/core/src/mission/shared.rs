//! One robot's mission in a fleet's shared work: the block it claims, the blocks the
//! other robots claim (left to them), and those they delivered (forgotten here).

use super::Mission;
use std::collections::BTreeSet;

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
        self.taken = taken;
        for &odd in elsewhere {
            if !self.delivered_markers.contains(&odd) {
                self.delivered_markers.extend([odd, odd + 1]);
                self.objects.forget(odd);
            }
        }
    }
}
