//! Maps: occupancy grids, the planning costmap, and, later, their files.

pub mod costmap;
pub mod grid;
