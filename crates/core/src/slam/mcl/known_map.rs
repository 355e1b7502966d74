//! The map MCL localises on: which cells are obstacles, which are known free (where
//! particles may be), and each cell's distance to the nearest obstacle, which both sensor
//! models read.

use crate::geometry::Point2;
use crate::map::grid::{OCCUPIED, OccupancyGrid};

/// A cell at least this occupied is an obstacle (map_server's trinary maps give 0 or 100).
const SOLID: i8 = OCCUPIED / 2;

/// Why a map cannot be localised on.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum KnownMapError {
    #[error("the map has no known free cell: particles have nowhere to be")]
    NoFreeSpace,
    #[error("the map has no occupied cell: a scan has nothing to match")]
    NoObstacles,
}

/// The corners of the box round the `occupied` cells of `grid` (at least one).
fn bounds_of(occupied: &[bool], grid: &OccupancyGrid) -> (Point2, Point2) {
    let (mut x0, mut y0, mut x1, mut y1) = (usize::MAX, usize::MAX, 0, 0);
    for (i, _) in occupied.iter().enumerate().filter(|(_, o)| **o) {
        let (cx, cy) = (i % grid.width, i / grid.width);
        (x0, y0, x1, y1) = (x0.min(cx), y0.min(cy), x1.max(cx), y1.max(cy));
    }
    let corner = |cx: usize, cy: usize| {
        Point2::new(
            grid.origin.x + cx as f64 * grid.resolution,
            grid.origin.y + cy as f64 * grid.resolution,
        )
    };
    (corner(x0, y0), corner(x1 + 1, y1 + 1))
}

/// See the module comment.
#[derive(Clone, Debug)]
pub struct KnownMap {
    pub width: usize,
    pub height: usize,
    pub resolution: f64,
    pub origin: Point2,
    occupied: Vec<bool>,
    /// Indices of the known free cells.
    free: Vec<u32>,
    /// Distance from each cell's centre to the nearest obstacle cell's centre, metres.
    distance: Vec<f32>,
    /// The lower-left and upper-right corners of the occupied cells: the mapped place,
    /// without the unknown margin round it.
    occupied_bounds: (Point2, Point2),
}

impl KnownMap {
    pub fn new(grid: &OccupancyGrid) -> Result<Self, KnownMapError> {
        let occupied: Vec<bool> = grid.cells.iter().map(|&c| c >= SOLID).collect();
        let free: Vec<u32> = (grid.cells.iter().enumerate())
            .filter(|&(_, &c)| c == 0)
            .map(|(i, _)| i as u32)
            .collect();
        if free.is_empty() {
            return Err(KnownMapError::NoFreeSpace);
        }
        if !occupied.iter().any(|&o| o) {
            return Err(KnownMapError::NoObstacles);
        }
        let occupied_bounds = bounds_of(&occupied, grid);
        let squared = squared_distance_transform(&occupied, grid.width, grid.height);
        let distance = squared
            .iter()
            .map(|&d2| (d2.sqrt() * grid.resolution) as f32)
            .collect();
        Ok(Self {
            width: grid.width,
            height: grid.height,
            resolution: grid.resolution,
            origin: grid.origin,
            occupied,
            free,
            distance,
            occupied_bounds,
        })
    }

    /// The lower-left and upper-right corners of the occupied cells.
    pub fn occupied_bounds(&self) -> (Point2, Point2) {
        self.occupied_bounds
    }

    /// The cell index holding `p`, if on the map.
    #[inline]
    pub fn index_of(&self, x: f64, y: f64) -> Option<usize> {
        let cx = ((x - self.origin.x) / self.resolution).floor();
        let cy = ((y - self.origin.y) / self.resolution).floor();
        (cx >= 0.0 && cy >= 0.0 && (cx as usize) < self.width && (cy as usize) < self.height)
            .then(|| cy as usize * self.width + cx as usize)
    }

    /// Distance to the nearest obstacle from the cell holding (x, y), metres; None off the map.
    #[inline]
    pub fn distance_at(&self, x: f64, y: f64) -> Option<f32> {
        self.index_of(x, y).map(|i| self.distance[i])
    }

    /// Distance of cell `i` to the nearest obstacle, metres.
    #[inline]
    pub fn distance_of(&self, i: usize) -> f32 {
        self.distance[i]
    }

    pub fn is_free(&self, p: Point2) -> bool {
        self.index_of(p.x, p.y)
            .is_some_and(|i| !self.occupied[i] && self.free.binary_search(&(i as u32)).is_ok())
    }

    /// Whether the map says anything of `p`: an obstacle or known free, not unknown and
    /// not off the map.
    pub fn is_known(&self, p: Point2) -> bool {
        self.index_of(p.x, p.y)
            .is_some_and(|i| self.occupied[i] || self.free.binary_search(&(i as u32)).is_ok())
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
    /// obstacle cell, up to `max_range`; off the map the beam meets nothing. The beam
    /// visits every cell it crosses (Amanatides and Woo, "A Fast Voxel Traversal
    /// Algorithm", 1987) wherever an obstacle is near; where the distance field says
    /// none is, it jumps ahead by that distance less a cell's diagonal (sphere tracing),
    /// which cannot pass over an obstacle cell.
    pub fn ray_cast(&self, x: f64, y: f64, c: f64, s: f64, max_range: f64) -> f64 {
        let inv = 1.0 / self.resolution;
        let (gx, gy) = ((x - self.origin.x) * inv, (y - self.origin.y) * inv);
        let (w, h) = (self.width as f64, self.height as f64);
        let t_max = max_range * inv;
        let mut t = 0.0;
        while t < t_max {
            let (px, py) = (gx + t * c, gy + t * s);
            if !(px >= 0.0 && py >= 0.0 && px < w && py < h) {
                return max_range;
            }
            let (ix, iy) = (px as usize, py as usize);
            let d = f64::from(self.distance[iy * self.width + ix]) * inv;
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

/// Farther than this from an obstacle (cells), a beam jumps instead of stepping.
const JUMP_FROM: f64 = 2.5;

/// Squared distance (in cells) from each cell to the nearest `true` cell: the exact
/// Euclidean transform of Felzenszwalb and Huttenlocher, "Distance Transforms of Sampled
/// Functions" (2012), one pass over columns and one over rows.
pub fn squared_distance_transform(seeds: &[bool], width: usize, height: usize) -> Vec<f64> {
    let far = ((width * width + height * height) as f64) * 4.0 + 1.0;
    let mut out: Vec<f64> = seeds.iter().map(|&s| if s { 0.0 } else { far }).collect();
    let n = width.max(height);
    let (mut f, mut d) = (vec![0.0; n], vec![0.0; n]);
    let (mut v, mut z) = (vec![0usize; n], vec![0.0; n + 1]);
    for x in 0..width {
        for y in 0..height {
            f[y] = out[y * width + x];
        }
        envelope(&f[..height], &mut d[..height], &mut v, &mut z);
        for y in 0..height {
            out[y * width + x] = d[y];
        }
    }
    for y in 0..height {
        let row = &mut out[y * width..(y + 1) * width];
        f[..width].copy_from_slice(row);
        envelope(&f[..width], &mut d[..width], &mut v, &mut z);
        row.copy_from_slice(&d[..width]);
    }
    out
}

/// One dimension of the transform: the lower envelope of the parabolas (q - p)² + f(p)
/// (Felzenszwalb and Huttenlocher 2012, algorithm DT(f)).
fn envelope(f: &[f64], d: &mut [f64], v: &mut [usize], z: &mut [f64]) {
    let n = f.len();
    if n == 0 {
        return;
    }
    let mut k = 0;
    v[0] = 0;
    z[0] = f64::NEG_INFINITY;
    z[1] = f64::INFINITY;
    for q in 1..n {
        loop {
            let p = v[k];
            // Where the parabola from q meets the one from p.
            let s = ((f[q] + (q * q) as f64) - (f[p] + (p * p) as f64)) / (2.0 * (q - p) as f64);
            if s <= z[k] && k > 0 {
                k -= 1;
                continue;
            }
            if s <= z[k] {
                // k == 0 and q's parabola is lower everywhere to the right of -inf.
                v[0] = q;
                z[1] = f64::INFINITY;
                break;
            }
            k += 1;
            v[k] = q;
            z[k] = s;
            z[k + 1] = f64::INFINITY;
            break;
        }
    }
    k = 0;
    for (q, out) in d.iter_mut().enumerate().take(n) {
        while z[k + 1] < q as f64 {
            k += 1;
        }
        let p = v[k];
        let dq = q as f64 - p as f64;
        *out = dq * dq + f[p];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn brute(seeds: &[bool], w: usize, h: usize) -> Vec<f64> {
        (0..w * h)
            .map(|i| {
                let (x, y) = ((i % w) as f64, (i / w) as f64);
                (0..w * h)
                    .filter(|&j| seeds[j])
                    .map(|j| {
                        let (a, b) = ((j % w) as f64, (j / w) as f64);
                        (x - a).powi(2) + (y - b).powi(2)
                    })
                    .fold(f64::INFINITY, f64::min)
            })
            .collect()
    }

    #[test]
    fn the_transform_matches_brute_force() {
        let (w, h) = (13, 9);
        let mut seeds = vec![false; w * h];
        for &i in &[0, 17, 40, 41, 88, 116] {
            seeds[i] = true;
        }
        assert_eq!(
            squared_distance_transform(&seeds, w, h),
            brute(&seeds, w, h)
        );
    }

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
