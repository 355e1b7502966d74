//! Barrier arms in the twin: an arm lower than the robot is solid where its shadow falls
//! on the floor, so a robot driving under a closing arm stops against it and the contact
//! is counted.

use super::Twin;
use crate::geometry::{Point2, Segment};
use crate::sim::shapes::segment_distance2;

/// The twin robot's height, metres (a TurtleBot3 Burger is 192 mm tall).
pub const ROBOT_HEIGHT: f64 = 0.192;

impl Twin {
    /// Whether moving the footprint's centre from `from` to `to` now runs it into a
    /// barrier's arm where the arm is lower than the robot.
    pub(super) fn arm_in_the_way(&self, from: Point2, to: Point2) -> bool {
        let Some(scene) = self.world.track.as_ref() else {
            return false;
        };
        let (now, r) = (self.time(), self.robot.footprint_radius);
        let reach = |b: &crate::sim::track::Barrier| {
            let (a, b) = b.low_reach(now, ROBOT_HEIGHT);
            Segment { a, b }
        };
        // Half the arm's thickness widens the footprint's reach.
        let r = r + crate::sim::track::ARM_THICKNESS / 2.0;
        scene.barriers.iter().any(|b| {
            let arm = reach(b);
            let before = segment_distance2(from, from, arm);
            // A footprint already touching may back away.
            segment_distance2(from, to, arm) < r * r && segment_distance2(to, to, arm) <= before
        })
    }

    /// Contacts with a barrier's arm so far.
    pub fn barrier_hits(&self) -> u32 {
        self.contacts.barrier_hits
    }
}
