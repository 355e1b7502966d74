//! After letting go: is the block where the robot left it, at its gate?

use super::{CHECK_TIME, Delivery, DropEvent, FOUND_NEAR};
use crate::mission::drop_places::{AT_GATE, at_gate, occupied_near};
use crate::mission::step::{Inputs, Motion};

impl Delivery {
    /// Whether the block let go is at its gate, as the robot can tell: the point it let go
    /// lies in the gate's region, and the lidar's map or the camera finds the block there
    /// within `CHECK_TIME`.
    pub(super) fn check(&self, inputs: &Inputs, waited: f64) -> DropEvent {
        let let_go = self.let_go.unwrap_or(inputs.pose.position());
        let off = let_go.distance(self.gate.center);
        let slot = self.slot;
        if !at_gate(&self.gate, let_go) {
            let why = format!("let go {off:.2} m from the gate's centre, beyond its {AT_GATE} m");
            return DropEvent::Missed { why, slot };
        }
        let map = inputs.map;
        let lidar = inputs.occupied.len() == map.width * map.height && !inputs.occupied.is_empty();
        let seen = (inputs.seen.iter()).any(|&id| id == self.block || id == self.block + 1);
        let found = seen || (lidar && occupied_near(map, inputs.occupied, let_go, FOUND_NEAR));
        let delivered = DropEvent::Delivered {
            at: let_go,
            slot: self.slot,
        };
        match () {
            _ if found => delivered,
            _ if waited < CHECK_TIME => DropEvent::Go(Motion::Stop, None),
            // Without a lidar, a block whose markers face away is not seen: the jaws
            // opened inside the gate's region, and that is what the robot knows.
            _ if !lidar => delivered,
            _ => DropEvent::Missed {
                why: format!(
                    "neither the lidar nor the camera finds it where it was let go, {off:.2} m from the gate's centre"
                ),
                slot,
            },
        }
    }
}
