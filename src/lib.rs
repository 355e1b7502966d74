//! navdeck: a terminal teleop-and-autonomy console for small differential-drive robots.

pub mod app;
pub mod arm;
pub mod arm_pick;
pub mod clock;
pub mod config;
pub mod console;
pub mod control;
pub mod data;
pub mod geometry;
pub mod headless;
pub mod keymap;
pub mod link;
pub mod map;
pub mod map_report;
pub mod mission;
pub mod mission_runner;
pub mod perception;
pub mod pilot;
pub mod plan;
pub mod plan_report;
pub mod session;
pub mod sim;
pub mod slam;
pub mod tour;
pub mod tui;
pub mod world_fit;
