//! Maps: occupancy grids and, later, their files.

pub mod grid;
