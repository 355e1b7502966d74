//! Driving the tag graph (seed 003 §2.3-§2.6): the controllers (`control`), the pose
//! from a tag and between tags (`reset`), and the route driver's phases (`driver`).

pub mod control;
pub mod driver;
pub mod reset;

#[cfg(test)]
mod driver_tests;

pub use control::DriveGains;
pub use driver::{DriveEvent, DriveSetup, Phase, TagDriver};
pub use reset::{PoseReference, TagSighting, over_point, pose_from_tag};
