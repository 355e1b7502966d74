//! Ground truth: what only a simulator knows about its robot and world. A link offers it
//! when there is a simulator behind it (the twin); links to real robots have none.
//!
//! It is for showing and scoring only (the true pose beside the estimate, accuracy,
//! collisions); nothing that decides how the robot moves may read it.

use super::{BlockState, Twin, World};
use crate::geometry::{Pose2, Twist};

/// Read-only truth of a simulated robot.
pub trait GroundTruth {
    /// The world the robot drives in.
    fn world(&self) -> &World;
    /// Simulated time, seconds.
    fn time(&self) -> f64;
    /// The robot's true pose.
    fn pose(&self) -> Pose2;
    /// The base's true twist.
    fn velocity(&self) -> Twist;
    /// The twist the robot was last told to drive at.
    fn command(&self) -> Twist;
    /// Where every block truly is.
    fn blocks(&self) -> &[BlockState];
    /// Contacts with walls and obstacles so far.
    fn collisions(&self) -> u32;
    /// True path length of the robot centre, metres.
    fn distance_driven(&self) -> f64;
    /// Contacts with a barrier's arm (a track's), also counted in `collisions`.
    fn barrier_hits(&self) -> u32 {
        0
    }
    /// Contacts with another robot of a fleet in the same world, also counted in
    /// `collisions`.
    fn robot_hits(&self) -> u32 {
        0
    }
}

impl GroundTruth for Twin {
    fn world(&self) -> &World {
        Twin::world(self)
    }
    fn time(&self) -> f64 {
        Twin::time(self)
    }
    fn pose(&self) -> Pose2 {
        Twin::pose(self)
    }
    fn velocity(&self) -> Twist {
        Twin::velocity(self)
    }
    fn command(&self) -> Twist {
        Twin::command(self)
    }
    fn blocks(&self) -> &[BlockState] {
        Twin::blocks(self)
    }
    fn collisions(&self) -> u32 {
        Twin::collisions(self)
    }
    fn distance_driven(&self) -> f64 {
        Twin::distance_driven(self)
    }
    fn barrier_hits(&self) -> u32 {
        Twin::barrier_hits(self)
    }
    fn robot_hits(&self) -> u32 {
        Twin::robot_hits(self)
    }
}

/// A log line for each contact `truth` counted since `logged`, which it updates.
pub fn collision_note(truth: &dyn GroundTruth, logged: &mut u32) -> Option<String> {
    let count = truth.collisions();
    if count <= *logged {
        return None;
    }
    *logged = count;
    let p = truth.pose();
    Some(format!(
        "collision at ({:.2}, {:.2}): robot stopped against an obstacle ({count} so far)",
        p.x, p.y
    ))
}
