//! The runners: navdeck without a terminal. Each drives one robot's runtime (or a
//! console, for `--headless`) on simulated time and reports for people or as JSON.

pub mod arm_pick;
pub mod faults;
pub mod fleet;
pub mod fleet_mission;
pub mod headless;
pub mod lane;
#[cfg(feature = "vision")]
pub mod lane_detect;
pub mod map_report;
pub mod mission;
pub mod plan_report;
pub mod route;
pub mod route_camera;
pub mod score;
pub mod slam_figures;
pub mod tour;
