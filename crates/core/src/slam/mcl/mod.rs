//! Monte-Carlo localisation on a known map with the lidar (seed 002; Probabilistic
//! Robotics chapter 8): particles moved by the odometry motion model, weighed by a
//! measurement model, resampled when their effective sample size falls, their count set
//! by KLD-sampling, and random particles added when the scans fit worse than they used
//! to (augmented MCL), so that a lost or kidnapped robot finds itself again.

pub mod beam_memo;
pub mod cluster;
pub mod config;
pub mod distance_transform;
mod filter;
pub mod known_map;
pub mod motion;
mod recovery;
pub mod resample;
pub mod rivals;
pub mod seek;
pub mod sensor;
mod status;

pub use filter::{Mcl, Particle, Phase, Status};
pub use known_map::{KnownMap, KnownMapError};
