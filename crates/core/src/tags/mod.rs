//! Tag-graph navigation's map (seed 003): AprilTags on the floor, the directed edges a
//! robot may drive between them, and named tasks; routes through it by BFS.
//!
//! - `file`: the tag map file (seed 003 §1.2.3's `map.yaml`) read and checked, each
//!   error naming the tag and the line.
//! - `graph`: BFS between tags, routes through a task's waypoints, blocked edges left out.
//! - `drive`: driving a route: pure pursuit, quarter turns, alignment, the pose reset.
//! - `floor`: the twin's world round a tag map, boxes on edges.
//! - `generate`: tag grids of random sizes with joins left out and boxes on edges.
//! - `scan`: the seed's scan list (§2.2 mode 4) from CSV: group ids to tags, a route from
//!   the dock through them and back.

pub mod drive;
pub mod file;
pub mod floor;
pub mod generate;
pub mod graph;
pub mod scan;

pub use file::{Direction, EdgeKind, Tag, TagEdge, TagId, TagKind, TagMap, TagMapError, Zone};
pub use graph::{Leg, Route, RouteError};
pub use scan::{ScanError, ScanRoute};
