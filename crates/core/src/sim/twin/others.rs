//! The other robots of a fleet sharing the twin's world: solid to its footprint, seen by
//! its lidar and hiding markers from its camera, and the blocks they move or carry.

use super::Twin;
use crate::geometry::{Point2, Pose2, Segment};
use crate::sim::BlockState;
use crate::sim::collision::Disc;

/// Sides of the polygon a neighbour's round footprint is drawn as for the lidar and the
/// camera (its corners on the circle, so the outline lies at most 1.3 % inside it).
const OUTLINE_SIDES: usize = 16;

/// Where another robot stands, for a twin that shares its world.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Neighbour {
    pub pose: Pose2,
    /// Radius of its round footprint, metres.
    pub radius: f64,
}

/// The fleet's other robots as this twin sees them, and its contacts with them.
#[derive(Clone, Debug, Default)]
pub(super) struct Others {
    pub(super) discs: Vec<Disc>,
    pub(super) outlines: Vec<Segment>,
    /// Contacts with another robot, also counted in the twin's collisions.
    pub(super) hits: u32,
}

impl Others {
    fn set(&mut self, neighbours: &[Neighbour]) {
        self.discs.clear();
        self.outlines.clear();
        for n in neighbours {
            let center = n.pose.position();
            self.discs.push(Disc {
                center,
                radius: n.radius,
            });
            let corner = |k: usize| {
                let a = n.pose.theta + k as f64 * std::f64::consts::TAU / OUTLINE_SIDES as f64;
                Point2::new(center.x + n.radius * a.cos(), center.y + n.radius * a.sin())
            };
            self.outlines.extend((0..OUTLINE_SIDES).map(|k| Segment {
                a: corner(k),
                b: corner(k + 1),
            }));
        }
    }

    /// Whether a footprint of radius `r` centred at `at` overlaps a neighbour.
    pub(super) fn touches(&self, at: Point2, r: f64) -> bool {
        (self.discs.iter()).any(|d| d.center.distance(at) < r + d.radius + 1e-9)
    }
}

impl Twin {
    /// The other robots in this twin's world as they stand now: until the next call they
    /// are solid to the footprint, seen by the lidar and hide markers from the camera.
    pub fn set_neighbours(&mut self, neighbours: &[Neighbour]) {
        self.others.set(neighbours);
    }

    /// Contacts with another robot so far (also in `collisions`).
    pub fn robot_hits(&self) -> u32 {
        self.others.hits
    }

    /// The block the gripper holds, by its index in the world's blocks.
    pub fn held_block(&self) -> Option<usize> {
        self.gripper.held()
    }

    /// Takes the fleet's view of the blocks this twin does not hold: where each lies, and
    /// whether another robot carries it (then it is out of sight and not solid here, as a
    /// held block is). Blocks are matched by index; extra entries are ignored.
    pub fn adopt_blocks(&mut self, shared: &[BlockState]) {
        let mine = self.gripper.held();
        for (i, (own, theirs)) in self.blocks.iter_mut().zip(shared).enumerate() {
            if mine == Some(i) || (own.pose == theirs.pose && own.held == theirs.held) {
                continue;
            }
            own.pose = theirs.pose;
            own.held = theirs.held;
            self.free_blocks.moved = true;
            if self.released == Some(i) {
                self.released = None;
            }
        }
    }
}
