//! The distances a generated world keeps, each with where it comes from.

/// Boundary and interior wall markers every this many metres (maps/arena.toml's spacing).
pub const MARKER_SPACING: f64 = 0.5;
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
/// Drop places sit 0.10 m either side of the gate centre, rows of two 0.12 m apart
/// (mission/delivery.rs SLOT_OFFSETS and ROW_DEPTH).
pub const DROP_SLOT: f64 = 0.10;
pub const DROP_ROW: f64 = 0.12;
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
/// 15 odd/even pairs per colour in 421-450 and 521-550 (seed 001 section 1).
pub const MAX_BLOCKS: usize = 30;
/// Four faces per box in 301-400 (seed 001 section 1).
pub const MAX_OBSTACLES: usize = 25;
/// Box sides are drawn from this range, metres (the arena's boxes are 0.2-0.4 m).
pub const BOX_SIDES: (f64, f64) = (0.2, 0.45);
