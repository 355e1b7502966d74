//! Zones to mask cells and back: a rectangle covers every cell it overlaps, and a mask's
//! cells of one value are joined into rectangles again (runs along a row, stacked while
//! the next row has the same run).

use super::Rect;
use crate::geometry::Point2;
use crate::map::costmap::{Costmap, INFLATED, LETHAL};
use crate::map::grid::OccupancyGrid;

/// A cell whose edge lies within this of a rectangle's edge is not counted as overlapped:
/// a rectangle on cell boundaries covers exactly its cells.
const EDGE_TOLERANCE: f64 = 1e-6;
/// A mask covering zones keeps this many cells beyond the farthest one.
const MARGIN_CELLS: usize = 2;

/// A grid's placement: cell side, lower-left corner and size in cells.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    pub resolution: f64,
    pub origin: Point2,
    pub width: usize,
    pub height: usize,
}

impl Frame {
    pub fn of(grid: &OccupancyGrid) -> Self {
        Self {
            resolution: grid.resolution,
            origin: grid.origin,
            width: grid.width,
            height: grid.height,
        }
    }

    /// This frame grown by whole cells until it covers every rectangle of `rects`.
    pub fn covering<'a>(self, rects: impl Iterator<Item = &'a Rect>) -> Self {
        let res = self.resolution;
        let (mut x0, mut y0) = (self.origin.x, self.origin.y);
        let (mut x1, mut y1) = (x0 + self.width as f64 * res, y0 + self.height as f64 * res);
        let mut any = false;
        for r in rects {
            any = true;
            x0 = x0.min(r.x0);
            y0 = y0.min(r.y0);
            x1 = x1.max(r.x1);
            y1 = y1.max(r.y1);
        }
        if !any {
            return self;
        }
        let margin = MARGIN_CELLS as f64;
        // Whole cells left of and below the old origin, so cells stay where they were.
        let left = ((self.origin.x - x0) / res).ceil().max(0.0) + margin;
        let below = ((self.origin.y - y0) / res).ceil().max(0.0) + margin;
        let origin = Point2::new(self.origin.x - left * res, self.origin.y - below * res);
        let width = ((x1 - origin.x) / res).ceil() as usize + MARGIN_CELLS;
        let height = ((y1 - origin.y) / res).ceil() as usize + MARGIN_CELLS;
        Self {
            resolution: res,
            origin,
            width: width.min(crate::map::pgm::MAX_SIDE),
            height: height.min(crate::map::pgm::MAX_SIDE),
        }
    }

    /// The inclusive column and row ranges of the cells `rect` overlaps, if any is on
    /// the grid.
    pub fn cells_of(&self, rect: &Rect) -> Option<((usize, usize), (usize, usize))> {
        let span = |lo: f64, hi: f64, origin: f64, n: usize| {
            let a = ((lo - origin) / self.resolution + EDGE_TOLERANCE).floor();
            let b = ((hi - origin) / self.resolution - EDGE_TOLERANCE).ceil() - 1.0;
            let (a, b) = (a.max(0.0), b.min(n as f64 - 1.0));
            (a <= b).then_some((a as usize, b as usize))
        };
        Some((
            span(rect.x0, rect.x1, self.origin.x, self.width)?,
            span(rect.y0, rect.y1, self.origin.y, self.height)?,
        ))
    }

    pub fn grid(&self, fill: i8) -> OccupancyGrid {
        OccupancyGrid::new(self.width, self.height, self.resolution, self.origin, fill)
    }
}

/// Each rectangle of `rects` painted onto `grid` with its value, the painter keeping
/// whichever of the old and new values `keep` picks.
pub fn paint(
    grid: &mut OccupancyGrid,
    rects: impl Iterator<Item = (Rect, i8)>,
    keep: impl Fn(i8, i8) -> i8,
) {
    let frame = Frame::of(grid);
    for (rect, value) in rects {
        let Some(((c0, c1), (r0, r1))) = frame.cells_of(&rect) else {
            continue;
        };
        for row in r0..=r1 {
            for col in c0..=c1 {
                let old = grid.get(col, row);
                grid.set(col, row, keep(old, value));
            }
        }
    }
}

/// The cells of `grid` that `label` gives a label, joined into rectangles (world frame),
/// each with its label: a rectangle painted with `paint` comes back whole.
pub fn rectangles(grid: &OccupancyGrid, label: impl Fn(i8) -> Option<u32>) -> Vec<(u32, Rect)> {
    // Open rectangles: (first column, last column, label) -> first row.
    let mut open: Vec<((usize, usize, u32), usize)> = Vec::new();
    let mut done = Vec::new();
    let res = grid.resolution;
    let close = |(c0, c1, l): (usize, usize, u32), r0: usize, r1: usize| {
        (
            l,
            Rect {
                x0: grid.origin.x + c0 as f64 * res,
                y0: grid.origin.y + r0 as f64 * res,
                x1: grid.origin.x + (c1 + 1) as f64 * res,
                y1: grid.origin.y + (r1 + 1) as f64 * res,
            },
        )
    };
    for row in 0..grid.height {
        let mut runs = Vec::new();
        let mut col = 0;
        while col < grid.width {
            let Some(l) = label(grid.get(col, row)) else {
                col += 1;
                continue;
            };
            let start = col;
            while col + 1 < grid.width && label(grid.get(col + 1, row)) == Some(l) {
                col += 1;
            }
            runs.push((start, col, l));
            col += 1;
        }
        let mut next = Vec::with_capacity(runs.len());
        for run in runs {
            match open.iter().position(|(key, _)| *key == run) {
                Some(k) => next.push(open.swap_remove(k)),
                None => next.push((run, row)),
            }
        }
        for (key, first) in open {
            done.push(close(key, first, row - 1));
        }
        open = next;
    }
    for (key, first) in open {
        done.push(close(key, first, grid.height - 1));
    }
    done
}

/// The keepout layer of a costmap: a cell within `lethal` metres of a keepout rectangle is
/// lethal, within `inflated` metres inflated, as a lidar hit marks the cells round it.
pub fn keepout_costs(map: &Costmap, rects: &[Rect], lethal: f64, inflated: f64) -> Vec<u8> {
    let mut cost = vec![0u8; map.width * map.height];
    let reach = lethal.max(inflated);
    let frame = Frame {
        resolution: map.resolution,
        origin: map.origin,
        width: map.width,
        height: map.height,
    };
    for r in rects {
        let grown = Rect {
            x0: r.x0 - reach,
            y0: r.y0 - reach,
            x1: r.x1 + reach,
            y1: r.y1 + reach,
        };
        let Some(((c0, c1), (r0, r1))) = frame.cells_of(&grown) else {
            continue;
        };
        for row in r0..=r1 {
            for col in c0..=c1 {
                let d = r.distance(map.center_of(col, row));
                let c = if d <= lethal || r.contains(map.center_of(col, row)) {
                    LETHAL
                } else if d <= inflated {
                    INFLATED
                } else {
                    0
                };
                let i = map.index(col, row);
                cost[i] = cost[i].max(c);
            }
        }
    }
    cost
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame() -> Frame {
        Frame {
            resolution: 0.05,
            origin: Point2::new(-1.0, -1.0),
            width: 40,
            height: 40,
        }
    }

    #[test]
    fn a_rectangle_on_cell_edges_covers_exactly_its_cells() {
        let r = Rect {
            x0: -0.5,
            y0: 0.0,
            x1: 0.5,
            y1: 0.25,
        };
        // (-0.5 + 1) / 0.05 = 10 .. (0.5 + 1) / 0.05 = 30, exclusive; rows 20..25.
        assert_eq!(frame().cells_of(&r), Some(((10, 29), (20, 24))));
        // Off the edge by a little: the partly covered cells count.
        let r2 = Rect { x1: 0.51, ..r };
        assert_eq!(frame().cells_of(&r2), Some(((10, 30), (20, 24))));
        let off = Rect {
            x0: 5.0,
            y0: 5.0,
            x1: 6.0,
            y1: 6.0,
        };
        assert_eq!(frame().cells_of(&off), None);
    }

    #[test]
    fn painted_rectangles_come_back_whole() {
        let mut grid = frame().grid(0);
        let a = Rect {
            x0: -0.5,
            y0: 0.0,
            x1: 0.5,
            y1: 0.25,
        };
        let b = Rect {
            x0: -0.9,
            y0: -0.9,
            x1: -0.7,
            y1: -0.3,
        };
        paint(&mut grid, [(a, 100), (b, 40)].into_iter(), |_, new| new);
        let mut found = rectangles(&grid, |v| (v > 0).then_some(v as u32));
        found.sort_by_key(|x| x.0);
        assert_eq!(found.len(), 2);
        let close = |p: &Rect, q: &Rect| {
            (p.x0 - q.x0).abs() < 1e-9
                && (p.y0 - q.y0).abs() < 1e-9
                && (p.x1 - q.x1).abs() < 1e-9
                && (p.y1 - q.y1).abs() < 1e-9
        };
        assert_eq!(found[0].0, 40);
        assert!(close(&found[0].1, &b), "{:?}", found[0].1);
        assert_eq!(found[1].0, 100);
        assert!(close(&found[1].1, &a), "{:?}", found[1].1);
    }

    #[test]
    fn an_l_shape_is_two_rectangles_covering_its_cells() {
        let mut grid = frame().grid(0);
        for row in 0..4 {
            grid.set(3, row, 100);
        }
        grid.set(4, 0, 100);
        let found = rectangles(&grid, |v| (v == 100).then_some(1));
        let cells: f64 = found.iter().map(|(_, r)| r.width() * r.height()).sum();
        assert!((cells / 0.0025 - 5.0).abs() < 1e-6, "{found:?}");
    }

    #[test]
    fn a_frame_grows_by_whole_cells_to_cover_zones() {
        let far = Rect {
            x0: 2.0,
            y0: -3.0,
            x1: 2.5,
            y1: -2.0,
        };
        let f = frame().covering([far].iter());
        // The old cells keep their place: the origin moved by whole cells.
        let shift = (f.origin.y - frame().origin.y) / 0.05;
        assert!((shift - shift.round()).abs() < 1e-9);
        assert!(f.cells_of(&far).is_some());
        assert!(f.origin.y <= -3.0 && f.origin.x + f.width as f64 * 0.05 >= 2.5);
    }

    #[test]
    fn keepout_cells_are_lethal_and_ringed() {
        let map = Costmap::new(40, 40, 0.05, Point2::new(-1.0, -1.0), 255);
        let r = Rect {
            x0: 0.0,
            y0: 0.0,
            x1: 0.5,
            y1: 0.5,
        };
        let cost = keepout_costs(&map, &[r], 0.15, 0.3);
        let at = |x: f64, y: f64| {
            let (c, r) = map.cell_of(Point2::new(x, y)).unwrap();
            cost[map.index(c, r)]
        };
        assert_eq!(at(0.25, 0.25), LETHAL);
        // Cell centres 0.075 and 0.175 m left of the zone.
        assert_eq!(at(-0.1, 0.25), LETHAL);
        assert_eq!(at(-0.2, 0.25), INFLATED);
        assert_eq!(at(-0.5, 0.25), 0);
    }
}
