//! The distances a generated world keeps, each with where it comes from.

use crate::mission::drop_places::{DROP_PLACES, DropPlace};

/// Boundary and interior wall markers every this many metres (maps/arena.toml's spacing),
/// unless asked otherwise.
pub const MARKER_SPACING: f64 = 0.5;
/// Marker spacings a world may ask for, metres: from 0.4 (a gate's 0.10 m markers 0.1 m
/// either side of its centre keep 0.05 m clear of boundary markers 0.2 m either side) to
/// 2 m (sparser than any flat the mission was measured in).
pub const MARKER_SPACINGS: (f64, f64) = (0.4, 2.0);
/// Doorway widths a world may ask for, metres: from 0.5 (the planner's 0.15 m lethal
/// radius each side and 0.2 m between) to 2 m (wider is no doorway).
pub const DOORWAYS: (f64, f64) = (0.5, 2.0);
/// Rooms are at least this wide, metres: a 0.8 m doorway and a block 0.5 m from its walls
/// both fit across one.
pub const MIN_ROOM: f64 = 1.2;
/// Distance between a gate's two markers, metres: maps/arena.toml's 0.2 m keeps each gate
/// marker's 0.10 m square 0.05 m clear of the boundary markers 0.25 m either side.
pub const GATE_WIDTH: f64 = 0.2;
/// Narrowest doorway, corridor or gap beside a box, metres (the issue "Autonomy in any
/// world": at least about 0.8 m, over twice the planner's 0.15 m lethal radius each side).
pub const MIN_PASSAGE: f64 = 0.8;
/// A block's centre keeps this far from every wall and box, metres: the mission plans to
/// 0.30 m from a block (`[mission] staging_distance`) with a 0.08 m body, plus 0.12 m.
pub const WALL_CLEARANCE: f64 = 0.5;
/// Block centres keep this far apart, metres: the body (0.08 m) at the 0.30 m staging
/// place of one block stays clear of the next, with a 0.2 m margin.
pub const MIN_BLOCK_SPACING: f64 = 0.6;
/// The start keeps this far from walls and boxes, metres (twice the planner's 0.15 m
/// lethal radius, `[map] lethal_radius`, less a little).
pub const START_CLEARANCE: f64 = 0.4;
/// Where the mission plans to before a block, metres (`[mission] staging_distance`).
pub const STAGING: f64 = 0.30;
/// Where the mission plans to before a gate, metres (`[mission] drop_staging`).
pub const DROP_STAGING: f64 = 0.40;
/// Robot centre to gate centre when the gripper opens, metres (`[mission] drop_distance`).
pub const DROP_DISTANCE: f64 = 0.18;
/// The lane's clearance below is set for drop places up to 0.10 m either side of the gate
/// centre (the first three sit 0.12 m apart, mission/drop_places.rs, a little wider).
pub const DROP_SLOT: f64 = 0.10;

/// The drop places the mission uses at a gate that takes `count` blocks, in the order it
/// fills them (at least the first).
pub fn drop_places(count: usize) -> &'static [DropPlace] {
    &DROP_PLACES[..count.clamp(1, DROP_PLACES.len())]
}
/// The lane a gate's drops use keeps this far from every solid but the gate's own wall,
/// metres: a drop place 0.10 m off the gate centre, the 0.08 m body, and 0.22 m to spare.
pub const GATE_CLEARANCE: f64 = 0.4;
/// Block centres and the start keep this far from a gate's drop lane, metres (a block
/// within 0.3 m of its gate counts as delivered, mission_runner.rs AT_GATE).
pub const GATE_KEEP_OUT: f64 = 0.5;
/// A wall's end keeps this far from the markers of the wall it meets, metres: half a
/// 0.10 m marker square ([vision.markers] boundary_side) and 0.07 m, so no marker is
/// half hidden by the joining wall.
pub const MARKER_END_CLEARANCE: f64 = 0.12;
/// Reachability is checked on cells this size, metres (twice the planner's 0.01 m).
pub const REACH_RESOLUTION: f64 = 0.02;
/// Cells this near a wall or box are closed to the robot's centre in the reachability
/// check, metres: the planner's lethal radius (`[map] lethal_radius` 0.15 = the 0.08 m
/// footprint plus the landmarks' uncertainty) and one and a half cells.
pub const REACH_RADIUS: f64 = 0.18;
/// Candidates drawn from one seed before giving up.
pub const ATTEMPTS: usize = 200;
/// Places tried for one box, block, gate or wall within a candidate.
pub const TRIES: usize = 100;
/// Longest side, metres: 12 m keeps the boundary (96 markers) and three interior walls on
/// both faces within the 300 boundary ids (seed 001 section 1).
pub const MAX_SIDE: f64 = 12.0;
/// Blocks of one colour: a gate's drop places (mission/drop_places.rs), fewer than the 15
/// odd/even pairs per colour in 421-450 and 521-550 (seed 001 section 1).
pub const MAX_PER_COLOUR: usize = DROP_PLACES.len();
/// Blocks in a world: both gates full.
pub const MAX_BLOCKS: usize = 2 * MAX_PER_COLOUR;
/// Four faces per box in 301-400 (seed 001 section 1).
pub const MAX_OBSTACLES: usize = 25;
/// Box sides are drawn from this range, metres (the arena's boxes are 0.2-0.4 m).
pub const BOX_SIDES: (f64, f64) = (0.2, 0.45);
