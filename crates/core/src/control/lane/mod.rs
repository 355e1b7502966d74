//! Lane following (seed 000 §2.4) and traffic compliance (§3): the lane pipeline's error
//! steers the robot by PD and slows it by the speed law; a red or yellow light near ahead
//! and a barrier down or moving near ahead hold it until green and up. Pure: each step
//! takes the time and the newest sighting.

mod arm_watch;
mod config;
mod driver;
mod light_watch;

pub use config::{LaneConfig, LaneDriveConfig};
pub use driver::{LaneDriver, LaneStep, Wait};
