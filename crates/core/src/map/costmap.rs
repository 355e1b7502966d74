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
        super::grid::cell_of(self.origin, self.resolution, (self.width, self.height), p)
    }

    /// World position of a cell's centre.
    pub fn center_of(&self, cx: usize, cy: usize) -> Point2 {
        super::grid::center_of(self.origin, self.resolution, cx, cy)
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

/// How a costmap cell looks on screen, least to most severe.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Shade {
    Unknown,
    Free,
    /// Near something: the safety gradient.
    Near,
    Inflated,
    Lethal,
}

impl Shade {
    pub const fn of(cost: u8) -> Self {
        match cost {
            NO_INFORMATION => Shade::Unknown,
            FREE => Shade::Free,
            c if c >= LETHAL => Shade::Lethal,
            c if c >= INFLATED => Shade::Inflated,
            _ => Shade::Near,
        }
    }
}

impl Costmap {
    /// Inclusive column range overlapping [x0, x1), if any lies on the map.
    pub fn columns_in(&self, x0: f64, x1: f64) -> Option<(usize, usize)> {
        super::grid::index_range(self.origin.x, self.resolution, self.width, x0, x1)
    }

    /// Inclusive row range overlapping [y0, y1), if any lies on the map.
    pub fn rows_in(&self, y0: f64, y1: f64) -> Option<(usize, usize)> {
        super::grid::index_range(self.origin.y, self.resolution, self.height, y0, y1)
    }

    /// The most severe shade in the inclusive block `cols` x `rows`: one screen cell's look.
    pub fn worst_in_cells(&self, (c0, c1): (usize, usize), (r0, r1): (usize, usize)) -> Shade {
        let mut worst = 0u8;
        for row in r0..=r1 {
            let line = &self.cost[row * self.width + c0..=row * self.width + c1];
            worst = line
                .iter()
                .fold(worst, |w, &c| w.max(SHADE_RANK[c as usize]));
            if worst == Shade::Lethal as u8 {
                break;
            }
        }
        SHADES[worst as usize]
    }
}

/// Shades by rank, and each cost's rank: a table keeps the drawing loop branch-free.
const SHADES: [Shade; 5] = [
    Shade::Unknown,
    Shade::Free,
    Shade::Near,
    Shade::Inflated,
    Shade::Lethal,
];
const SHADE_RANK: [u8; 256] = {
    let mut table = [0u8; 256];
    let mut c = 0;
    while c < 256 {
        table[c] = Shade::of(c as u8) as u8;
        c += 1;
    }
    table
};

/// Whether a plan may never enter a cell of this cost.
pub fn is_lethal(cost: u8) -> bool {
    (LETHAL..NO_INFORMATION).contains(&cost)
}
