//! The collision monitor (`[safety]`): zones around the robot that stop, slow or limit a
//! command when obstacle points lie in them, or that scale it so a predicted contact stays
//! some seconds away, after Nav2's collision monitor. It sits between whatever asks for
//! motion (keys, the follower, the mission) and the robot, in every mode.
//!
//! Pure: the caller passes the obstacle points in the robot's frame (`points_from_scan`,
//! or `points_from_grid` for a robot without a lidar), their age and the command, and
//! sends the verdict's command.
//!
//! ```
//! use navdeck_core::control::collision_monitor::{
//!     CollisionMonitor, Obstacles, SafetyConfig, SourceKind,
//! };
//! use navdeck_core::geometry::{Point2, Twist};
//!
//! let monitor = CollisionMonitor::new(&SafetyConfig::default(), 0.105);
//! // A wall 0.14 m ahead of the robot's centre, inside the default 0.15 m stop zone.
//! let wall: Vec<Point2> = (-5..=5).map(|k| Point2::new(0.14, k as f64 * 0.01)).collect();
//! let obstacles = Obstacles { points: &wall, age: Some(0.1), source: SourceKind::Scan };
//! let ahead = monitor.check(Twist::new(0.2, 0.0), &obstacles);
//! assert_eq!(ahead.command, Twist::ZERO);
//! let back = monitor.check(Twist::new(-0.2, 0.0), &obstacles);
//! assert_eq!(back.command, Twist::new(-0.2, 0.0));
//! ```

pub mod approach;
pub mod config;
pub mod monitor;
pub mod outline;
pub mod shape;
pub mod sources;
pub mod validate;
pub mod verdict;
pub mod zone;

#[cfg(test)]
mod data_tests;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod wall_tests;

pub use config::{ActionType, PolygonConfig, SafetyConfig};
pub use monitor::CollisionMonitor;
pub use sources::{Obstacles, SourceKind, points_from_grid, points_from_scan};
pub use verdict::{Acted, Verdict};
