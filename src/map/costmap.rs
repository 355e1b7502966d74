//! The planning costmap: one byte per cell, seed 001's 0.0..1.0 cell value scaled to 0..100.

use crate::geometry::Point2;

/// A cell nothing is known about yet.
pub const NO_INFORMATION: u8 = 255;
/// An occupied cell: never entered by a plan.
pub const LETHAL: u8 = 100;
/// Seed 001 section 4: cells within the inflation radius of a marker get value 0.7.
pub const INFLATED: u8 = 70;
/// Known free and far from everything.
pub const FREE: u8 = 0;

/// A row-major costmap; cell (0, 0) is the lower-left corner at `origin`.
#[derive(Clone, Debug, PartialEq)]
pub struct Costmap {
    pub width: usize,
    pub height: usize,
    /// Cell side, metres.
    pub resolution: f64,
    /// World position of the lower-left corner of cell (0, 0).
    pub origin: Point2,
    /// `FREE..=LETHAL`, or `NO_INFORMATION`.
    pub cost: Vec<u8>,
}

impl Costmap {
    pub fn new(width: usize, height: usize, resolution: f64, origin: Point2, fill: u8) -> Self {
        Self {
            width,
            height,
            resolution,
            origin,
            cost: vec![fill; width * height],
        }
    }

    /// Index of cell (cx, cy) in `cost`.
    pub fn index(&self, cx: usize, cy: usize) -> usize {
        cy * self.width + cx
    }

    /// Cell holding world point `p`, if it lies on the map (seed 001 `world_to_grid`).
    pub fn cell_of(&self, p: Point2) -> Option<(usize, usize)> {
        let cx = ((p.x - self.origin.x) / self.resolution).floor();
        let cy = ((p.y - self.origin.y) / self.resolution).floor();
        if !(cx >= 0.0 && cy >= 0.0 && cx < self.width as f64 && cy < self.height as f64) {
            return None;
        }
        Some((cx as usize, cy as usize))
    }

    /// World position of a cell's centre.
    pub fn center_of(&self, cx: usize, cy: usize) -> Point2 {
        Point2::new(
            self.origin.x + (cx as f64 + 0.5) * self.resolution,
            self.origin.y + (cy as f64 + 0.5) * self.resolution,
        )
    }

    pub fn get(&self, cx: usize, cy: usize) -> u8 {
        self.cost[self.index(cx, cy)]
    }

    pub fn set(&mut self, cx: usize, cy: usize, cost: u8) {
        let i = self.index(cx, cy);
        self.cost[i] = cost;
    }

    /// Cost at a world point; no information off the map.
    pub fn at(&self, p: Point2) -> u8 {
        self.cell_of(p)
            .map_or(NO_INFORMATION, |(cx, cy)| self.get(cx, cy))
    }
}

/// Whether a plan may never enter a cell of this cost.
pub fn is_lethal(cost: u8) -> bool {
    (LETHAL..NO_INFORMATION).contains(&cost)
}
