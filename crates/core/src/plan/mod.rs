//! Planning on the costmap: A*, path post-processing and the velocity profile.
//!
//! [`pipeline::Planner::plan`] runs the whole chain: an 8-connected A* with integer costs and
//! seed 001's safety penalty ([`astar`]), collinear removal ([`simplify`], seed 001),
//! line-of-sight shortcutting that never raises the worst cell cost ([`shortcut`], seed 002),
//! cubic B-spline smoothing checked against the costmap ([`smooth`], seed 004 section A) and a
//! curvature- and acceleration-limited velocity profile ([`profile`], seed 004 section B).
//! Nothing here reads a clock or a terminal; every step is a pure function of its inputs
//! except for the search buffers the planner reuses.

pub mod astar;
pub mod bspline;
pub mod bucket_queue;
pub mod config;
pub mod error;
pub mod pipeline;
pub mod profile;
pub mod segment_cells;
pub mod shortcut;
pub mod simplify;
pub mod smooth;
pub mod trajectory;

pub use astar::{AStar, CellPath, SearchOptions};
pub use config::PlanConfig;
pub use error::PlanError;
pub use pipeline::{Plan, Planner};
pub use smooth::{PathSample, Smoothing};
