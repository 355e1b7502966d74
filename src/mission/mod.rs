//! The autonomous mission of seed 001 sections 7-8: explore, find blocks and gates, pick
//! each block up and deliver it. Pure state: landmarks and time in, commands out.

pub mod objects;
pub mod step;
pub mod targets;
