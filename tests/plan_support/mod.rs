//! Grids and reference searches shared by the planning tests and the A* benchmark, a
//! file each. This file gathers what benches/astar.rs uses (it includes it by path); the
//! tests declare the files they use, as for tests/common (see its README).

pub mod arena;
pub mod reference;

pub use arena::arena;
pub use reference::pathfinding_astar;
