//! Maps: the planning costmap the robot builds from landmarks and scans, occupancy grids,
//! their files, and how a map agrees with the true walls (truth.rs).

pub mod agreement;
pub mod belief;
pub mod config;
pub mod contact;
pub mod costmap;
pub mod evidence;
pub mod grid;
pub mod io;
pub mod landmark_layer;
pub mod pgm;
pub mod raw_map;
pub mod reach;
pub mod stamp;
pub mod truth;
pub mod zones;
