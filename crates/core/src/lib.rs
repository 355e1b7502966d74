//! navdeck's data and pure core: what crosses a link, geometry, the twin, EKF-SLAM and
//! MCL, maps, planning, control, the mission, the arm and perception. Nothing here reads
//! a clock, touches a terminal or opens a socket; time and randomness are passed in.

pub mod arm;
pub mod clock;
pub mod control;
pub mod data;
pub mod geometry;
pub mod health;
pub mod map;
pub mod mission;
pub mod perception;
pub mod plan;
pub mod sim;
pub mod slam;
pub mod tags;
