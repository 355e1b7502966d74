//! The autonomous mission of seed 001 sections 7-8: explore, find blocks and gates, pick
//! each block up and deliver it. Pure state: landmarks and time in, commands out.

mod arm_moves;
mod block_fit;
pub mod block_fusion;
mod choose;
pub mod claims;
mod clearance;
mod clusters;
pub mod config;
pub mod coverage;
mod delivery;
mod drive;
pub mod drop_places;
mod explored;
pub mod fleet_explored;
mod fleet_wait;
mod found;
pub mod frontier_claims;
mod gate_side;
mod leg;
pub mod machine;
pub mod objects;
mod phase;
mod pickup;
mod resume;
pub mod shared;
pub mod step;
pub mod targets;
mod unexplained;
mod view;

pub use arm_moves::ABOVE as ARM_ABOVE;
pub use config::{MissionConfig, TargetRule};

/// How far ahead of the robot's centre a block stands when `arm` reaches for it, the
/// mission's way (`[mission] arm_standoff`, or nearer where the arm reaches no further).
pub fn arm_reach(arm: &crate::arm::ArmConfig, standoff: f64, mid: f64) -> f64 {
    arm_moves::ArmMoves::new(arm.clone()).reach_from_centre(standoff, mid)
}
pub use machine::{Mission, TimelineEntry};
