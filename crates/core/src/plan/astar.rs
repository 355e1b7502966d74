//! A* on the costmap (seed 001 section 5): f(n) = g(n) + h(n) + safety_cost(n), 8-connected.
//!
//! Costs are integers so results are exact and comparable: a cardinal step costs 1000, a
//! diagonal 1414 (seed 001: 1.0 and sqrt 2), and entering a cell adds seed 001's safety penalty
//! 5.0 x value, value = cost / 100, i.e. 50 x cost in thousandths. The buffers are flat arrays
//! indexed by cell and stamped with a generation, so a reused [`AStar`] never clears them.

use super::bucket_queue::{BucketQueue, SPAN};
use super::error::PlanError;
use crate::map::costmap::{Costmap, LETHAL, NO_INFORMATION, is_lethal};

/// Seed 001 section 5: a cardinal move costs 1.0 cell, in thousandths.
pub const CARDINAL: u32 = 1000;
/// Seed 001 section 5: a diagonal move costs sqrt 2 cells, in thousandths.
pub const DIAGONAL: u32 = 1414;
/// Seed 001 section 5: safety_penalty = 5.0 x value with value = cost / 100, in thousandths.
pub const PENALTY_PER_COST: u32 = 50;

/// Marks an impassable cell in the step-penalty table.
const BLOCKED: u32 = u32::MAX;

/// What the search may enter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SearchOptions {
    /// Whether `NO_INFORMATION` cells may be entered.
    pub allow_unknown: bool,
    /// The cost an unknown cell counts as when entered (below `LETHAL`).
    pub unknown_cost: u8,
}

impl Default for SearchOptions {
    fn default() -> Self {
        Self {
            allow_unknown: true,
            unknown_cost: 0,
        }
    }
}

impl SearchOptions {
    /// The cost a cell of raw value `raw` counts as, or `None` if it may not be entered.
    pub fn traversal_cost(&self, raw: u8) -> Option<u8> {
        if raw == NO_INFORMATION {
            (self.allow_unknown && self.unknown_cost < LETHAL).then_some(self.unknown_cost)
        } else if is_lethal(raw) {
            None
        } else {
            Some(raw)
        }
    }

    /// The penalty, in thousandths of a cell, of entering a cell of raw value `raw`.
    pub fn entry_penalty(&self, raw: u8) -> Option<u32> {
        self.traversal_cost(raw)
            .map(|c| PENALTY_PER_COST * u32::from(c))
    }
}

/// The octile distance in thousandths: exact on an empty 8-connected grid, so admissible and
/// consistent. Seed 001 uses Manhattan, which overestimates diagonal travel here (not
/// admissible); octile is the 8-connected distance (Russell & Norvig, AIMA 3.6).
pub fn octile(dx: u32, dy: u32) -> u32 {
    let (lo, hi) = if dx < dy { (dx, dy) } else { (dy, dx) };
    CARDINAL * hi + (DIAGONAL - CARDINAL) * lo
}

/// A path found by [`AStar::search`].
#[derive(Clone, Debug, PartialEq)]
pub struct CellPath {
    /// Cells from start to goal inclusive.
    pub cells: Vec<(usize, usize)>,
    /// Total cost in thousandths of a cell step.
    pub cost: u64,
    /// Cells taken off the open list.
    pub expanded: usize,
}

impl CellPath {
    /// Total cost in cell units (a cardinal step is 1.0).
    pub fn cost_cells(&self) -> f64 {
        self.cost as f64 / f64::from(CARDINAL)
    }
}

/// A reusable A* search: owns its buffers so repeated plans allocate nothing.
#[derive(Debug, Default)]
pub struct AStar {
    /// Per cell, one cache line's worth of search state.
    nodes: Vec<Node>,
    generation: u32,
    /// The open list keyed by f; f never decreases as the heuristic is consistent.
    open: BucketQueue,
}

/// The search state of one cell.
#[derive(Clone, Copy, Debug, Default)]
struct Node {
    /// Cheapest known cost from the start, valid when `stamp` is this generation's.
    g: u32,
    parent: u32,
    /// `generation`: open with a valid g; `generation + 1`: closed; anything less: unseen.
    stamp: u32,
}

// The ring must span the largest rise of f over one step: the step, its penalty and the
// heuristic's change.
const _: () = assert!(DIAGONAL + PENALTY_PER_COST * (LETHAL as u32 - 1) + DIAGONAL < SPAN);

/// Neighbour steps: (dx, dy, cost); the first four are cardinal.
const STEPS: [(i32, i32, u32); 8] = [
    (1, 0, CARDINAL),
    (-1, 0, CARDINAL),
    (0, 1, CARDINAL),
    (0, -1, CARDINAL),
    (1, 1, DIAGONAL),
    (-1, 1, DIAGONAL),
    (1, -1, DIAGONAL),
    (-1, -1, DIAGONAL),
];

/// For each diagonal step in `STEPS`, the two cardinal steps beside it.
const CORNERS: [(usize, usize); 4] = [(0, 2), (1, 2), (0, 3), (1, 3)];

impl AStar {
    pub fn new() -> Self {
        Self::default()
    }

    /// Starts a new generation, resizing or (rarely, on wrap-around) clearing the stamps.
    fn begin(&mut self, cells: usize) {
        if self.nodes.len() != cells || self.generation >= u32::MAX - 2 {
            self.nodes = vec![Node::default(); cells];
            self.generation = 0;
        }
        self.generation += 2;
    }

    /// Cheapest path between two cells. The start cell may be lethal (the robot is where it
    /// is); the goal may not. Cells are (column, row).
    pub fn search(
        &mut self,
        map: &Costmap,
        start: (usize, usize),
        goal: (usize, usize),
        options: &SearchOptions,
    ) -> Result<CellPath, PlanError> {
        let (w, h) = (map.width, map.height);
        for (which, (cx, cy)) in [("start", start), ("goal", goal)] {
            if cx >= w || cy >= h {
                let p = map.center_of(cx, cy);
                return Err(PlanError::OffMap {
                    which,
                    x: p.x,
                    y: p.y,
                });
            }
        }
        assert!(
            w * h <= u32::MAX as usize,
            "costmap too large for 32-bit cell indices"
        );
        let goal_raw = map.get(goal.0, goal.1);
        let gp = map.center_of(goal.0, goal.1);
        if goal_raw == NO_INFORMATION && options.traversal_cost(goal_raw).is_none() {
            return Err(PlanError::GoalUnknown { x: gp.x, y: gp.y });
        }
        if is_lethal(goal_raw) {
            return Err(PlanError::GoalInObstacle {
                x: gp.x,
                y: gp.y,
                cost: goal_raw,
            });
        }

        let mut penalty = [BLOCKED; 256];
        for (raw, p) in penalty.iter_mut().enumerate() {
            if let Some(v) = options.entry_penalty(raw as u8) {
                *p = v;
            }
        }
        self.begin(w * h);
        let (open, closed) = (self.generation, self.generation + 1);
        let cost = &map.cost[..w * h];
        let (gx, gy) = (goal.0 as u32, goal.1 as u32);
        let si = map.index(start.0, start.1);
        let gi = map.index(goal.0, goal.1) as u32;
        self.nodes[si] = Node {
            g: 0,
            parent: si as u32,
            stamp: open,
        };
        let h0 = octile(
            start.0.abs_diff(goal.0) as u32,
            start.1.abs_diff(goal.1) as u32,
        );
        self.open.reset(h0);
        self.open.push(h0, si as u32);
        let nodes = &mut self.nodes[..w * h];
        let mut expanded = 0usize;
        let (wi, hi) = (w as i32, h as i32);
        let offsets = STEPS.map(|(dx, dy, _)| dy as isize * w as isize + dx as isize);

        while let Some((_, i)) = self.open.pop() {
            let iu = i as usize;
            if nodes[iu].stamp == closed {
                continue; // a stale entry: the cell was reached more cheaply since
            }
            nodes[iu].stamp = closed;
            expanded += 1;
            if i == gi {
                return Ok(self.trace(map, si, gi as usize, expanded));
            }
            let (x, y) = ((i % w as u32) as i32, (i / w as u32) as i32);
            // Away from the edges no neighbour needs a bounds test.
            let interior = x > 0 && y > 0 && x + 1 < wi && y + 1 < hi;
            let gi_cost = nodes[iu].g;
            let mut free = [false; 4];
            for (k, &(dx, dy, step)) in STEPS.iter().enumerate() {
                let (nx, ny) = (x + dx, y + dy);
                if !interior && (nx < 0 || ny < 0 || nx >= wi || ny >= hi) {
                    continue;
                }
                let j = iu.wrapping_add_signed(offsets[k]);
                let pen = penalty[cost[j] as usize];
                if k < 4 {
                    free[k] = pen != BLOCKED;
                }
                if pen == BLOCKED {
                    continue;
                }
                // No squeezing diagonally between two blocked cardinal neighbours.
                if k >= 4 {
                    let (a, b) = CORNERS[k - 4];
                    if !free[a] && !free[b] {
                        continue;
                    }
                }
                let ng = gi_cost.saturating_add(step + pen);
                let node = &mut nodes[j];
                // A closed cell already holds its cheapest g, so the test below spares it.
                if node.stamp < open || ng < node.g {
                    *node = Node {
                        g: ng,
                        parent: i,
                        stamp: open,
                    };
                    let hj = octile((nx as u32).abs_diff(gx), (ny as u32).abs_diff(gy));
                    self.open.push(ng.saturating_add(hj), j as u32);
                }
            }
        }
        Err(PlanError::Unreachable {
            x: gp.x,
            y: gp.y,
            expanded,
        })
    }

    /// Walks the parents back from the goal.
    fn trace(&self, map: &Costmap, start: usize, goal: usize, expanded: usize) -> CellPath {
        let mut cells = vec![];
        let mut i = goal;
        loop {
            cells.push((i % map.width, i / map.width));
            if i == start {
                break;
            }
            i = self.nodes[i].parent as usize;
        }
        cells.reverse();
        CellPath {
            cells,
            cost: u64::from(self.nodes[goal].g),
            expanded,
        }
    }
}
