//! navdeck: a terminal teleop-and-autonomy console for small differential-drive robots.
//!
//! This crate is the top of the house: the console, the keymap, the command line and its
//! runners. The layers below are crates of their own (`crates/`), re-exported here under
//! the names the rest of navdeck and its tests use.

pub use navdeck_core::{
    arm, clock, control, data, geometry, health, map, mission, perception, plan, sim, slam, tags,
};
pub use navdeck_link::{self as link, record};
pub use navdeck_msgs as msgs;
pub use navdeck_pilot as pilot;

pub mod app;
pub mod config;
pub mod console;
pub mod fleet;
pub mod keymap;
pub mod replay;
pub mod runners;
pub mod session;
pub mod tui;
pub mod world_fit;
