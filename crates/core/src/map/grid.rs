//! An occupancy grid in nav_msgs/OccupancyGrid's convention: -1 unknown, 0 free .. 100 occupied.

use crate::geometry::Point2;

pub const UNKNOWN: i8 = -1;
pub const FREE: i8 = 0;
pub const OCCUPIED: i8 = 100;

/// A row-major grid; cell (0, 0) is the lower-left corner at `origin`.
#[derive(Clone, Debug, PartialEq)]
pub struct OccupancyGrid {
    pub width: usize,
    pub height: usize,
    /// Cell side, metres.
    pub resolution: f64,
    /// World position of the lower-left corner of cell (0, 0).
    pub origin: Point2,
    pub cells: Vec<i8>,
}

impl OccupancyGrid {
    pub fn new(width: usize, height: usize, resolution: f64, origin: Point2, fill: i8) -> Self {
        Self {
            width,
            height,
            resolution,
            origin,
            cells: vec![fill; width * height],
        }
    }

    /// Cell holding world point `p`, if it lies on the grid (seed 001 `world_to_grid`).
    pub fn cell_of(&self, p: Point2) -> Option<(usize, usize)> {
        cell_of(self.origin, self.resolution, (self.width, self.height), p)
    }

    /// World position of a cell's centre.
    pub fn center_of(&self, cx: usize, cy: usize) -> Point2 {
        center_of(self.origin, self.resolution, cx, cy)
    }

    pub fn get(&self, cx: usize, cy: usize) -> i8 {
        self.cells[cy * self.width + cx]
    }

    pub fn set(&mut self, cx: usize, cy: usize, value: i8) {
        self.cells[cy * self.width + cx] = value;
    }

    /// Value at a world point; unknown off the grid.
    pub fn at(&self, p: Point2) -> i8 {
        self.cell_of(p).map_or(UNKNOWN, |(cx, cy)| self.get(cx, cy))
    }

    /// Width and height in metres.
    pub fn extent(&self) -> (f64, f64) {
        (
            self.width as f64 * self.resolution,
            self.height as f64 * self.resolution,
        )
    }

    /// The highest value among cells overlapping the world rectangle [x0, x1) x [y0, y1):
    /// occupied wins over free, free over unknown. Used to draw a grid coarser than it is.
    pub fn max_in(&self, x0: f64, y0: f64, x1: f64, y1: f64) -> i8 {
        match (self.columns_in(x0, x1), self.rows_in(y0, y1)) {
            (Some(cols), Some(rows)) => self.max_in_cells(cols, rows),
            _ => UNKNOWN,
        }
    }

    /// Inclusive column range overlapping [x0, x1), if any lies on the grid.
    pub fn columns_in(&self, x0: f64, x1: f64) -> Option<(usize, usize)> {
        index_range(self.origin.x, self.resolution, self.width, x0, x1)
    }

    /// Inclusive row range overlapping [y0, y1), if any lies on the grid.
    pub fn rows_in(&self, y0: f64, y1: f64) -> Option<(usize, usize)> {
        index_range(self.origin.y, self.resolution, self.height, y0, y1)
    }

    /// The highest value in the inclusive block of cells `cols` x `rows`.
    pub fn max_in_cells(&self, (c0, c1): (usize, usize), (r0, r1): (usize, usize)) -> i8 {
        let mut best = UNKNOWN;
        for row in r0..=r1 {
            let line = &self.cells[row * self.width + c0..=row * self.width + c1];
            for &v in line {
                if v > best {
                    best = v;
                    if best >= OCCUPIED {
                        return best;
                    }
                }
            }
        }
        best
    }
}

/// The cell of a `size` grid of `resolution` cells from `origin` that holds `p`, if any
/// (seed 001 `world_to_grid`, with the grid's corner rather than its centre as origin).
pub(crate) fn cell_of(
    origin: Point2,
    resolution: f64,
    (width, height): (usize, usize),
    p: Point2,
) -> Option<(usize, usize)> {
    let cx = ((p.x - origin.x) / resolution).floor();
    let cy = ((p.y - origin.y) / resolution).floor();
    // Written so that NaN lands outside too.
    if !(cx >= 0.0 && cy >= 0.0 && cx < width as f64 && cy < height as f64) {
        return None;
    }
    Some((cx as usize, cy as usize))
}

/// World position of the centre of cell (cx, cy).
pub(crate) fn center_of(origin: Point2, resolution: f64, cx: usize, cy: usize) -> Point2 {
    Point2::new(
        origin.x + (cx as f64 + 0.5) * resolution,
        origin.y + (cy as f64 + 0.5) * resolution,
    )
}

/// Cells of one axis (origin, cell size, count) overlapping [lo, hi), clamped to the grid.
pub(crate) fn index_range(
    origin: f64,
    resolution: f64,
    count: usize,
    lo: f64,
    hi: f64,
) -> Option<(usize, usize)> {
    let first = ((lo - origin) / resolution).floor().max(0.0);
    let last = ((hi - 1e-9 - origin) / resolution)
        .floor()
        .min(count as f64 - 1.0);
    (first <= last).then_some((first as usize, last as usize))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn world_to_cell_matches_seed_001_convention() {
        // Seed 001 section 4: 4 m x 4 m at 1 cm, centred on (0, 0): (x + 2) / 0.01.
        let g = OccupancyGrid::new(400, 400, 0.01, Point2::new(-2.0, -2.0), FREE);
        assert_eq!(g.cell_of(Point2::new(0.0, 0.0)), Some((200, 200)));
        assert_eq!(g.cell_of(Point2::new(-1.995, 1.999)), Some((0, 399)));
        assert_eq!(g.cell_of(Point2::new(2.0, 0.0)), None);
    }

    #[test]
    fn max_in_prefers_occupied() {
        let mut g = OccupancyGrid::new(10, 10, 0.1, Point2::new(0.0, 0.0), FREE);
        g.set(3, 4, OCCUPIED);
        assert_eq!(g.max_in(0.25, 0.35, 0.45, 0.55), OCCUPIED);
        assert_eq!(g.max_in(0.5, 0.5, 0.9, 0.9), FREE);
        assert_eq!(g.max_in(2.0, 2.0, 3.0, 3.0), UNKNOWN);
    }
}
