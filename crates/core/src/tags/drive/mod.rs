//! Driving the tag graph (seed 003 §2.3-§2.6): the controllers (`control`), the pose
//! from a tag and between tags (`reset`), the route driver's phases (`driver`), and a
//! task driven with its blocked legs routed round (`route_run`).

pub mod control;
pub mod driver;
pub mod reset;
pub mod route_run;

#[cfg(test)]
mod driver_tests;

pub use control::DriveGains;
pub use driver::{DriveEvent, DriveSetup, Phase, TagDriver};
pub use reset::{PoseReference, TagSighting, over_point, pose_from_tag};
pub use route_run::RouteRun;
