//! After letting go: is the block where the robot left it, at its gate?

use super::{CHECK_TIME, Delivery, DropEvent, FOUND_NEAR};
use crate::geometry::Point2;
use crate::mission::drop_places::{AT_GATE, at_gate, occupied_near};
use crate::mission::step::{Inputs, Motion};

impl Delivery {
    /// Whether the block let go is at its gate, as the robot can tell: the point it let go
    /// lies in the gate's region, and the lidar (its newest scan or its map) or the camera
    /// finds the block there within `CHECK_TIME`.
    pub(super) fn check(&self, inputs: &Inputs, waited: f64) -> DropEvent {
        let let_go = self.let_go.unwrap_or(inputs.pose.position());
        let map = inputs.map;
        let mapped = inputs.occupied.len() == map.width * map.height && !inputs.occupied.is_empty();
        let lidar = mapped || !inputs.scan.is_empty();
        let seen = (inputs.seen.iter()).any(|&id| id == self.block || id == self.block + 1);
        // The newest scan, before the map has folded it in.
        let scanned = (inputs.scan.iter())
            .any(|&p| inputs.pose.transform_point(p).distance(let_go) <= FOUND_NEAR);
        let found =
            seen || scanned || (mapped && occupied_near(map, inputs.occupied, let_go, FOUND_NEAR));
        match () {
            _ if !found && waited < CHECK_TIME => DropEvent::Go(Motion::Stop, None),
            // Without a lidar, a block whose markers face away is not seen: the jaws
            // opened inside the gate's region, and that is what the robot knows.
            _ if found || !lidar => self.judge(let_go),
            _ => DropEvent::Missed {
                why: format!(
                    "neither the lidar nor the camera finds it where it was let go, {:.2} m from the gate's centre",
                    let_go.distance(self.gate.center)
                ),
                slot: self.slot,
                at: let_go,
            },
        }
    }

    /// Delivered when the block let go at `at` is at the gate.
    fn judge(&self, at: Point2) -> DropEvent {
        let slot = self.slot;
        if at_gate(&self.gate, at) {
            return DropEvent::Delivered { at, slot };
        }
        let off = at.distance(self.gate.center);
        let why = format!("let go {off:.2} m from the gate's centre, beyond its {AT_GATE} m");
        DropEvent::Missed { why, slot, at }
    }
}
