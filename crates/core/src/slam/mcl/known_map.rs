//! The map MCL localises on: which cells are obstacles, which are known free (where
//! particles may be), and each cell's distance to the nearest obstacle, which both sensor
//! models read. The distances are kept only in a window round the obstacles, as far out
//! as any model reads them (`reach`): a map drawn in a corner of a large unknown image
//! costs what its mapped part does, not the image's square.

use super::distance_transform::squared_distance_transform;
use crate::geometry::Point2;
use crate::map::grid::{OCCUPIED, OccupancyGrid};

/// A cell at least this occupied is an obstacle (map_server's trinary maps give 0 or 100).
const SOLID: i8 = OCCUPIED / 2;

/// How far from an obstacle distances are kept when no model says: AMCL's default
/// `laser_likelihood_max_dist`, 2 m.
pub const DEFAULT_REACH: f64 = 2.0;

/// Why a map cannot be localised on.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum KnownMapError {
    #[error("the map has no known free cell: particles have nowhere to be")]
    NoFreeSpace,
    #[error("the map has no occupied cell: a scan has nothing to match")]
    NoObstacles,
}

/// A rectangle of cells: columns x0..x1, rows y0..y1.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct CellBox {
    x0: usize,
    y0: usize,
    x1: usize,
    y1: usize,
}

impl CellBox {
    fn width(&self) -> usize {
        self.x1 - self.x0
    }

    fn height(&self) -> usize {
        self.y1 - self.y0
    }

    /// The box's own index of grid cell (cx, cy), if inside.
    #[inline]
    fn index(&self, cx: usize, cy: usize) -> Option<usize> {
        (cx >= self.x0 && cx < self.x1 && cy >= self.y0 && cy < self.y1)
            .then(|| (cy - self.y0) * self.width() + (cx - self.x0))
    }
}

/// The box round the cells of `grid` at least `SOLID`, or None when there are none.
fn solid_box(grid: &OccupancyGrid) -> Option<CellBox> {
    let (mut x0, mut y0, mut x1, mut y1) = (usize::MAX, usize::MAX, 0, 0);
    for (i, _) in grid.cells.iter().enumerate().filter(|(_, c)| **c >= SOLID) {
        let (cx, cy) = (i % grid.width, i / grid.width);
        (x0, y0, x1, y1) = (x0.min(cx), y0.min(cy), x1.max(cx + 1), y1.max(cy + 1));
    }
    (x0 < x1).then_some(CellBox { x0, y0, x1, y1 })
}

/// See the module comment.
#[derive(Clone, Debug)]
pub struct KnownMap {
    pub width: usize,
    pub height: usize,
    pub resolution: f64,
    pub origin: Point2,
    /// Indices of the known free cells.
    free: Vec<u32>,
    /// The cells whose distances are kept: the obstacles' box widened by `reach`, in
    /// cells of the grid widened by `pad` on every side, so that the distances go on past
    /// the grid's edge: a wall drawn on a map's very edge (a map cropped tight, or the
    /// twin's own) is as near to a scan's end just past it as to one just inside.
    window: CellBox,
    pad: usize,
    /// Distance from each window cell's centre to the nearest obstacle cell's centre,
    /// metres; every cell outside the window is farther than `reach`.
    distance: Vec<f32>,
    reach: f64,
    /// The lower-left and upper-right corners of the occupied cells: the mapped place,
    /// without the unknown margin round it.
    occupied_bounds: (Point2, Point2),
}

impl KnownMap {
    /// The map of `grid`, distances kept out to `DEFAULT_REACH`.
    pub fn new(grid: &OccupancyGrid) -> Result<Self, KnownMapError> {
        Self::with_reach(grid, DEFAULT_REACH)
    }

    /// The map of `grid`, each cell's distance to the nearest obstacle kept where it is
    /// at most `reach` metres; farther cells read as infinitely far.
    pub fn with_reach(grid: &OccupancyGrid, reach: f64) -> Result<Self, KnownMapError> {
        let free: Vec<u32> = (grid.cells.iter().enumerate())
            .filter(|&(_, &c)| c == 0)
            .map(|(i, _)| i as u32)
            .collect();
        if free.is_empty() {
            return Err(KnownMapError::NoFreeSpace);
        }
        let solid = solid_box(grid).ok_or(KnownMapError::NoObstacles)?;
        let corner = |cx: usize, cy: usize| {
            Point2::new(
                grid.origin.x + cx as f64 * grid.resolution,
                grid.origin.y + cy as f64 * grid.resolution,
            )
        };
        let occupied_bounds = (corner(solid.x0, solid.y0), corner(solid.x1, solid.y1));
        // A cell `margin` cells beyond the box is more than `reach` from every obstacle.
        let margin = (reach.max(0.0) / grid.resolution).ceil().min(1e9) as usize + 1;
        // The grid widened by `pad` cells on every side: by the margin, or by the grid's
        // own size when that is less (no scan ends farther past the edge of the map it
        // matches than the map is across).
        let pad = margin.min(grid.width.max(grid.height));
        let window = CellBox {
            x0: (solid.x0 + pad).saturating_sub(margin),
            y0: (solid.y0 + pad).saturating_sub(margin),
            x1: (solid.x1 + pad + margin).min(grid.width + 2 * pad),
            y1: (solid.y1 + pad + margin).min(grid.height + 2 * pad),
        };
        let (ww, wh) = (window.width(), window.height());
        let mut seeds = Vec::with_capacity(ww * wh);
        for py in window.y0..window.y1 {
            for px in window.x0..window.x1 {
                let (cx, cy) = (px.wrapping_sub(pad), py.wrapping_sub(pad));
                let on_grid = cx < grid.width && cy < grid.height;
                seeds.push(on_grid && grid.cells[cy * grid.width + cx] >= SOLID);
            }
        }
        let squared = squared_distance_transform(&seeds, ww, wh);
        drop(seeds);
        let distance = squared
            .iter()
            .map(|&d2| (d2.sqrt() * grid.resolution) as f32)
            .collect();
        Ok(Self {
            width: grid.width,
            height: grid.height,
            resolution: grid.resolution,
            origin: grid.origin,
            free,
            window,
            pad,
            distance,
            reach,
            occupied_bounds,
        })
    }

    /// The lower-left and upper-right corners of the occupied cells.
    pub fn occupied_bounds(&self) -> (Point2, Point2) {
        self.occupied_bounds
    }

    /// How far from an obstacle distances are kept, metres.
    pub fn reach(&self) -> f64 {
        self.reach
    }

    /// The cell index holding `p`, if on the map.
    #[inline]
    pub fn index_of(&self, x: f64, y: f64) -> Option<usize> {
        let cx = ((x - self.origin.x) / self.resolution).floor();
        let cy = ((y - self.origin.y) / self.resolution).floor();
        (cx >= 0.0 && cy >= 0.0 && (cx as usize) < self.width && (cy as usize) < self.height)
            .then(|| cy as usize * self.width + cx as usize)
    }

    /// The window's own index of the cell holding (x, y): the position of its distance in
    /// `near_distances`, if the window holds it.
    #[inline]
    pub fn near_index_at(&self, x: f64, y: f64) -> Option<usize> {
        let px = ((x - self.origin.x) / self.resolution).floor() + self.pad as f64;
        let py = ((y - self.origin.y) / self.resolution).floor() + self.pad as f64;
        (px >= 0.0 && py >= 0.0 && px < usize::MAX as f64 && py < usize::MAX as f64)
            .then(|| self.window.index(px as usize, py as usize))
            .flatten()
    }

    /// The window's own index of cell `i`, if the window holds it.
    #[inline]
    fn near(&self, i: usize) -> Option<usize> {
        (self.window).index(i % self.width + self.pad, i / self.width + self.pad)
    }

    /// Distance to the nearest obstacle from the cell holding (x, y), metres (infinite
    /// farther than `reach`); None off the map.
    #[inline]
    pub fn distance_at(&self, x: f64, y: f64) -> Option<f32> {
        self.index_of(x, y).map(|i| self.distance_of(i))
    }

    /// Distance of cell `i` to the nearest obstacle, metres; infinite farther than `reach`.
    #[inline]
    pub fn distance_of(&self, i: usize) -> f32 {
        self.near(i).map_or(f32::INFINITY, |k| self.distance[k])
    }

    /// The distances kept, in the order of `near_index_at`'s indices: the window's, on
    /// the grid and past its edge.
    pub fn near_distances(&self) -> impl Iterator<Item = f32> + '_ {
        self.distance.iter().copied()
    }

    /// How many distances `near_distances` gives.
    pub fn near_count(&self) -> usize {
        self.distance.len()
    }

    fn is_occupied(&self, i: usize) -> bool {
        self.near(i).is_some_and(|k| self.distance[k] == 0.0)
    }

    pub fn is_free(&self, p: Point2) -> bool {
        self.index_of(p.x, p.y)
            .is_some_and(|i| self.free.binary_search(&(i as u32)).is_ok())
    }

    /// Whether the map says anything of `p`: an obstacle or known free, not unknown and
    /// not off the map.
    pub fn is_known(&self, p: Point2) -> bool {
        self.index_of(p.x, p.y)
            .is_some_and(|i| self.is_occupied(i) || self.free.binary_search(&(i as u32)).is_ok())
    }

    pub fn cells(&self) -> usize {
        self.width * self.height
    }

    pub fn free_cells(&self) -> &[u32] {
        &self.free
    }

    /// The centre of cell `i`.
    pub fn center(&self, i: usize) -> Point2 {
        let (cx, cy) = (i % self.width, i / self.width);
        Point2::new(
            self.origin.x + (cx as f64 + 0.5) * self.resolution,
            self.origin.y + (cy as f64 + 0.5) * self.resolution,
        )
    }

    /// The range at which a beam from `(x, y)` along the unit direction `(c, s)` meets an
    /// obstacle cell, up to `max_range`; a beam that misses the window round the
    /// obstacles meets nothing. The beam visits every cell it crosses (Amanatides and
    /// Woo, "A Fast Voxel Traversal Algorithm", 1987) wherever an obstacle is near; where
    /// the distance field says none is, it jumps ahead by that distance less a cell's
    /// diagonal (sphere tracing), which cannot pass over an obstacle cell.
    pub fn ray_cast(&self, x: f64, y: f64, c: f64, s: f64, max_range: f64) -> f64 {
        let inv = 1.0 / self.resolution;
        // In the widened grid's cells, as the window is.
        let pad = self.pad as f64;
        let (gx, gy) = (
            (x - self.origin.x) * inv + pad,
            (y - self.origin.y) * inv + pad,
        );
        if self.index_of(x, y).is_none() {
            return max_range;
        }
        let w = &self.window;
        let t_max = max_range * inv;
        // Where the beam is inside the window (slab test): outside it nothing is hit.
        let Some((enter, leave)) = slab(gx, c, w.x0 as f64, w.x1 as f64)
            .zip(slab(gy, s, w.y0 as f64, w.y1 as f64))
            .map(|((a0, a1), (b0, b1))| (a0.max(b0).max(0.0), a1.min(b1)))
        else {
            return max_range;
        };
        let mut t = enter;
        while t < t_max && t < leave {
            let (px, py) = (gx + t * c, gy + t * s);
            // Clamped: at the window's edge rounding may put the point a hair outside.
            // A beam on a cell's edge going down the axis is in the cell below: else the
            // next edge would be the one it stands on and it would never move on.
            let cell = |p: f64, step: f64| {
                let i = p.max(0.0) as usize;
                if step < 0.0 && p <= i as f64 {
                    i.saturating_sub(1)
                } else {
                    i
                }
            };
            let ix = cell(px, c).clamp(w.x0, w.x1 - 1);
            let iy = cell(py, s).clamp(w.y0, w.y1 - 1);
            let k = (iy - w.y0) * w.width() + (ix - w.x0);
            let d = f64::from(self.distance[k]) * inv;
            if d == 0.0 {
                return t * self.resolution;
            }
            if d > JUMP_FROM {
                t += d - std::f64::consts::SQRT_2;
                continue;
            }
            // On to the next cell boundary the beam crosses.
            let tx = if c > 0.0 {
                (ix as f64 + 1.0 - gx) / c
            } else if c < 0.0 {
                (ix as f64 - gx) / c
            } else {
                f64::INFINITY
            };
            let ty = if s > 0.0 {
                (iy as f64 + 1.0 - gy) / s
            } else if s < 0.0 {
                (iy as f64 - gy) / s
            } else {
                f64::INFINITY
            };
            t = tx.min(ty).max(t) + 1e-9;
        }
        max_range
    }
}

/// The interval of t over which `from + t * step` lies in lo..hi, if any.
fn slab(from: f64, step: f64, lo: f64, hi: f64) -> Option<(f64, f64)> {
    if step == 0.0 {
        return (lo..hi)
            .contains(&from)
            .then_some((f64::NEG_INFINITY, f64::INFINITY));
    }
    let (a, b) = ((lo - from) / step, (hi - from) / step);
    let (enter, leave) = (a.min(b), a.max(b));
    (enter < leave).then_some((enter, leave))
}

/// Farther than this from an obstacle (cells), a beam jumps instead of stepping.
const JUMP_FROM: f64 = 2.5;

#[cfg(test)]
mod tests {
    use super::*;

    fn room() -> OccupancyGrid {
        // 2 m x 1 m at 0.1 m: a wall all round, free inside.
        let mut g = OccupancyGrid::new(20, 10, 0.1, Point2::new(0.0, 0.0), 0);
        for x in 0..20 {
            g.set(x, 0, 100);
            g.set(x, 9, 100);
        }
        for y in 0..10 {
            g.set(0, y, 100);
            g.set(19, y, 100);
        }
        g
    }

    #[test]
    fn the_occupied_bounds_leave_out_the_unknown_margin() {
        // The room drawn inside a larger image with unknown (-1) all round it.
        let mut g = OccupancyGrid::new(40, 30, 0.1, Point2::new(-1.0, -1.0), -1);
        let inner = room();
        for y in 0..10 {
            for x in 0..20 {
                g.set(x + 5, y + 8, inner.get(x, y));
            }
        }
        let (lo, hi) = KnownMap::new(&g).unwrap().occupied_bounds();
        assert!(lo.distance(Point2::new(-0.5, -0.2)) < 1e-9, "{lo:?}");
        assert!(hi.distance(Point2::new(1.5, 0.8)) < 1e-9, "{hi:?}");
    }

    #[test]
    fn distances_are_kept_only_round_the_obstacles_and_rays_still_reach_them() {
        // The 2 m x 1 m room in the middle of a 40 m x 40 m unknown image at 0.1 m.
        let mut g = OccupancyGrid::new(400, 400, 0.1, Point2::new(-20.0, -20.0), -1);
        let inner = room();
        for y in 0..10 {
            for x in 0..20 {
                g.set(x + 190, y + 195, inner.get(x, y));
            }
        }
        let map = KnownMap::with_reach(&g, 1.0).unwrap();
        // The room and 1.1 m round it, not the image's 160,000 cells.
        assert_eq!(map.near_count(), 42 * 32);
        assert_eq!(map.distance_at(-15.0, -15.0), Some(f32::INFINITY));
        assert_eq!(map.distance_at(-1.45, 0.05), Some(0.5));
        // From far outside the kept window a beam still meets the room's west wall,
        // which starts at x = -1 m; one that passes the room meets nothing.
        let r = map.ray_cast(-15.0, 0.05, 1.0, 0.0, 100.0);
        assert!((r - 14.0).abs() < 1e-6, "{r}");
        assert_eq!(map.ray_cast(-15.0, 5.0, 1.0, 0.0, 100.0), 100.0);
        assert!(map.is_free(Point2::new(0.05, 0.05)));
        assert!(!map.is_known(Point2::new(-15.0, -15.0)));
        assert!(map.is_known(Point2::new(-0.95, 0.05)));
    }

    #[test]
    fn a_wall_on_the_maps_edge_is_near_a_scan_end_just_past_it() {
        // The room's walls are its grid's outermost cells: an end 0.1 m and 0.3 m west of
        // the west wall's cell is that far from it, not infinitely far.
        let map = KnownMap::new(&room()).unwrap();
        let distances: Vec<f32> = map.near_distances().collect();
        let at = |x: f64| distances[map.near_index_at(x, 0.55).expect("kept past the edge")];
        assert!((at(-0.05) - 0.1).abs() < 1e-3, "{}", at(-0.05));
        assert!((at(-0.25) - 0.3).abs() < 1e-3, "{}", at(-0.25));
        // Farther than the reach, nothing is kept.
        assert_eq!(map.near_index_at(-3.0, 0.55), None);
        // Off the map no particle may stand, and no cell index is given.
        assert_eq!(map.index_of(-0.05, 0.55), None);
    }

    #[test]
    fn a_ray_from_a_cell_corner_along_an_axis_moves_on() {
        let map = KnownMap::new(&room()).unwrap();
        // cos(90°) is not quite 0: from a cell's corner the beam runs up (and down) its
        // column's edge, barely leaning west, and must still reach the wall 0.4 m off.
        let lean = -std::f64::consts::FRAC_PI_2.cos();
        let up = map.ray_cast(1.0, 0.5, lean, 1.0, 3.5);
        let down = map.ray_cast(1.0, 0.5, lean, -1.0, 3.5);
        assert!(
            (up - 0.4).abs() < 0.06 && (down - 0.4).abs() < 0.06,
            "{up} {down}"
        );
    }

    #[test]
    fn a_ray_stops_at_the_wall() {
        let map = KnownMap::new(&room()).unwrap();
        // From x = 0.55 towards +x: the wall cell starts at x = 1.9.
        let r = map.ray_cast(0.55, 0.55, 1.0, 0.0, 3.5);
        assert!((1.3..=1.4).contains(&r), "{r}");
        // Towards -y: the wall cell ends at y = 0.1.
        let r = map.ray_cast(0.55, 0.55, 0.0, -1.0, 3.5);
        assert!((0.4..=0.5).contains(&r), "{r}");
        // Short of the range limit, the beam reports the limit.
        assert_eq!(map.ray_cast(0.55, 0.55, 1.0, 0.0, 0.5), 0.5);
    }

    #[test]
    fn maps_without_free_space_or_obstacles_are_refused() {
        let all_wall = OccupancyGrid::new(4, 4, 0.1, Point2::new(0.0, 0.0), 100);
        assert_eq!(
            KnownMap::new(&all_wall).unwrap_err(),
            KnownMapError::NoFreeSpace
        );
        let open = OccupancyGrid::new(4, 4, 0.1, Point2::new(0.0, 0.0), 0);
        assert_eq!(
            KnownMap::new(&open).unwrap_err(),
            KnownMapError::NoObstacles
        );
    }

    #[test]
    fn rays_meet_the_first_obstacle_cell_they_cross() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        // 3 m x 2 m at 0.05 m with random obstacle cells.
        let mut g = OccupancyGrid::new(60, 40, 0.05, Point2::new(-1.0, -1.0), 0);
        for _ in 0..120 {
            g.set(rng.random_range(0..60), rng.random_range(0..40), 100);
        }
        let map = KnownMap::new(&g).unwrap();
        for _ in 0..2000 {
            let (x, y) = (rng.random_range(-1.0..2.0), rng.random_range(-1.0..1.0));
            if map.distance_at(x, y) == Some(0.0) {
                continue;
            }
            let a: f64 = rng.random_range(-3.2..3.2);
            let (c, s) = (a.cos(), a.sin());
            // Brute force: 0.1 mm steps.
            let mut t = 0.0;
            let truth = loop {
                if t >= 3.5 {
                    break 3.5;
                }
                match map.distance_at(x + t * c, y + t * s) {
                    None => break 3.5,
                    Some(0.0) => break t,
                    _ => t += 1e-4,
                }
            };
            let r = map.ray_cast(x, y, c, s, 3.5);
            assert!(
                (r - truth).abs() < 2e-4,
                "from ({x}, {y}) at {a}: {r} vs {truth}"
            );
        }
    }
}
