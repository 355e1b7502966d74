//! The floor seen from above: a texture of the floor with the lane's tape painted on it
//! (and, under the shadows lighting, the shadows laid over it), a few millimetres a cell,
//! and its mipmap pyramid of box-filtered halvings (Williams 1983, "Pyramidal
//! parametrics") so far tape is averaged rather than sampled and does not flicker.

use super::palette::{self, Hsv};
use crate::geometry::Point2;
use crate::sim::track::Track;

/// Finest cell, metres.
const FINEST_CELL: f64 = 0.005;
/// Most cells in the finest level; a larger floor gets coarser cells.
const MOST_CELLS: f64 = 4.0e6;
/// Levels of the pyramid, each of cells twice the side of the one before.
pub const LEVELS: usize = 6;
/// Subsamples a side within a cell: tape and shadow edges are covered in 16ths.
const SUB: usize = 4;
/// A shadow lets through this fraction of the light (the brief's x0.45).
pub const SHADOW: f64 = 0.45;

/// One level of the pyramid.
#[derive(Clone)]
pub(super) struct Level {
    pub(super) inv_cell: f32,
    pub(super) width: usize,
    pub(super) height: usize,
    pub(super) texels: Vec<[u8; 4]>,
}

/// The floor's colours before lighting, over a rectangle of the world.
#[derive(Clone)]
pub struct FloorTexture {
    pub(super) x0: f32,
    pub(super) y0: f32,
    pub(super) levels: Vec<Level>,
    /// The bare floor, outside the rectangle.
    pub(super) outside: [u8; 3],
}

/// Where the finest level's cells lie: origin, cell side and counts.
struct Grid {
    x0: f64,
    y0: f64,
    cell: f64,
    width: usize,
    height: usize,
}

impl Grid {
    /// The cells whose centres lie within `margin` of the box `lo`-`hi`, clamped.
    fn cells_near(&self, lo: Point2, hi: Point2, margin: f64) -> (usize, usize, usize, usize) {
        let ix = |x: f64| ((x - self.x0) / self.cell).floor().max(0.0) as usize;
        let iy = |y: f64| ((y - self.y0) / self.cell).floor().max(0.0) as usize;
        (
            ix(lo.x - margin),
            iy(lo.y - margin),
            (ix(hi.x + margin) + 1).min(self.width),
            (iy(hi.y + margin) + 1).min(self.height),
        )
    }

    /// The world point of subsample `k` of cell (`cx`, `cy`).
    fn subsample(&self, cx: usize, cy: usize, k: usize) -> Point2 {
        let (sx, sy) = (k % SUB, k / SUB);
        Point2::new(
            self.x0 + (cx as f64 + (sx as f64 + 0.5) / SUB as f64) * self.cell,
            self.y0 + (cy as f64 + (sy as f64 + 0.5) / SUB as f64) * self.cell,
        )
    }
}

/// A painted line: a closed polyline, its width, and its dashes (`dash` on, `dash` off
/// along the centreline's arc length), if dashed.
struct Tape<'a> {
    points: &'a [Point2],
    step: f64,
    half_width: f64,
    dash: Option<f64>,
}

impl FloorTexture {
    /// The floor over `lo`-`hi` with `track`'s tape and the convex `shadows` painted on.
    pub fn new(lo: Point2, hi: Point2, track: &Track, shadows: &[Vec<Point2>]) -> Self {
        let area = ((hi.x - lo.x) * (hi.y - lo.y)).max(1e-6);
        let cell = FINEST_CELL.max((area / MOST_CELLS).sqrt());
        // Sides a multiple of the coarsest cell, so each halving is exact.
        let block = 1usize << (LEVELS - 1);
        let cells = |span: f64| ((span / cell).ceil() as usize).div_ceil(block).max(1) * block;
        let grid = Grid {
            x0: lo.x,
            y0: lo.y,
            cell,
            width: cells(hi.x - lo.x),
            height: cells(hi.y - lo.y),
        };
        let n = grid.width * grid.height;
        let step = track.length() / track.points().len() as f64;
        let half = track.lane_width / 2.0;
        let (left, right) = (track.offset_line(half), track.offset_line(-half));
        let mut yellow = vec![0u16; n];
        paint_tape(
            &grid,
            &mut yellow,
            &Tape {
                points: &left,
                step,
                half_width: track.line_width / 2.0,
                dash: None,
            },
        );
        let mut white = vec![0u16; n];
        paint_tape(
            &grid,
            &mut white,
            &Tape {
                points: &right,
                step,
                half_width: track.line_width / 2.0,
                dash: track.white_dashed.then_some(track.dash.max(0.005)),
            },
        );
        let mut shade = vec![0u16; n];
        for polygon in shadows {
            paint_polygon(&grid, &mut shade, polygon);
        }
        let colour = |c: Hsv| palette::bgr(c);
        let (floor, tape_y, tape_w) = (
            colour(palette::FLOOR),
            colour(palette::YELLOW_TAPE),
            colour(palette::WHITE_TAPE),
        );
        let whole = (SUB * SUB) as f64;
        let texels = (0..n)
            .map(|i| {
                let cy = f64::from(yellow[i].count_ones()) / whole;
                let cw = (f64::from(white[i].count_ones()) / whole).min(1.0 - cy);
                // Coverage-weighted mix (area sampling), darkened by the shadow's cover.
                let dark = 1.0 - (1.0 - SHADOW) * f64::from(shade[i].count_ones()) / whole;
                let mix = |k: usize| floor[k] * (1.0 - cy - cw) + tape_y[k] * cy + tape_w[k] * cw;
                // Four bytes a texel (the fourth unused) so each is one aligned load.
                [0, 1, 2, 3].map(|k| (mix(k.min(2)) * dark).round().clamp(0.0, 255.0) as u8)
            })
            .collect();
        let mut levels = vec![Level {
            inv_cell: (1.0 / cell) as f32,
            width: grid.width,
            height: grid.height,
            texels,
        }];
        for _ in 1..LEVELS {
            let next = halve(levels.last().expect("a level"));
            levels.push(next);
        }
        Self {
            x0: lo.x as f32,
            y0: lo.y as f32,
            levels,
            outside: palette::bytes(floor, 1.0),
        }
    }

    /// The finest cell's side, metres.
    pub fn cell(&self) -> f64 {
        1.0 / f64::from(self.levels[0].inv_cell)
    }

    /// The colour at world (`x`, `y`) by sampling `code`: 0 bilinear on the finest level
    /// (where the camera magnifies it, near the robot), `1 + level` the nearest cell of
    /// `level`. One point at a time, plainly: what `scanline`'s rows must give.
    #[cfg(test)]
    pub fn sample(&self, code: u8, x: f32, y: f32) -> [u8; 3] {
        let l = self.level_of(code);
        let gx = (x - self.x0) * l.inv_cell;
        let gy = (y - self.y0) * l.inv_cell;
        if !(gx >= 0.0 && gy >= 0.0) {
            return self.outside;
        }
        let (w, h) = (l.width, l.height);
        if code > 0 {
            let (ix, iy) = (gx as usize, gy as usize);
            return if ix < w && iy < h {
                let [b, g, r, _] = l.texels[iy * w + ix];
                [b, g, r]
            } else {
                self.outside
            };
        }
        // Texel centres at half cells: bilinear weights from the offset past them.
        let fx = ((gx - 0.5).max(0.0) * 256.0) as u32;
        let fy = ((gy - 0.5).max(0.0) * 256.0) as u32;
        let (ix, iy) = ((fx >> 8) as usize, (fy >> 8) as usize);
        if ix + 1 >= w || iy + 1 >= h {
            return self.outside;
        }
        let (ax, ay) = (fx & 255, fy & 255);
        let i = iy * w + ix;
        let (p00, p10) = (l.texels[i], l.texels[i + 1]);
        let (p01, p11) = (l.texels[i + w], l.texels[i + w + 1]);
        [0, 1, 2].map(|k| {
            let top = u32::from(p00[k]) * (256 - ax) + u32::from(p10[k]) * ax;
            let bottom = u32::from(p01[k]) * (256 - ax) + u32::from(p11[k]) * ax;
            ((top * (256 - ay) + bottom * ay + 32768) >> 16) as u8
        })
    }

    /// The level `code` samples (0 and 1 both the finest).
    pub(super) fn level_of(&self, code: u8) -> &Level {
        &self.levels[usize::from(code.saturating_sub(1)).min(LEVELS - 1)]
    }
}

impl std::fmt::Debug for FloorTexture {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let l = &self.levels[0];
        write!(
            f,
            "FloorTexture {{ {}x{} cells of {:.4} m from ({}, {}) }}",
            l.width,
            l.height,
            self.cell(),
            self.x0,
            self.y0
        )
    }
}

/// The level of half the cells: each texel the mean of the 2x2 below it (box filter).
fn halve(l: &Level) -> Level {
    let (w, h) = (l.width / 2, l.height / 2);
    let mut texels = Vec::with_capacity(w * h);
    for y in 0..h {
        for x in 0..w {
            let i = 2 * y * l.width + 2 * x;
            let q = [i, i + 1, i + l.width, i + l.width + 1].map(|j| l.texels[j]);
            texels.push([0, 1, 2, 3].map(|k| {
                let sum: u32 = q.iter().map(|p| u32::from(p[k])).sum();
                ((sum + 2) / 4) as u8
            }));
        }
    }
    Level {
        inv_cell: l.inv_cell / 2.0,
        width: w,
        height: h,
        texels,
    }
}

/// Sets the bits of the subsamples within the tape's half width of its polyline (and on a
/// dash, when dashed).
fn paint_tape(grid: &Grid, mask: &mut [u16], tape: &Tape) {
    let n = tape.points.len();
    let reach = tape.half_width + grid.cell;
    for i in 0..n {
        let (a, b) = (tape.points[i], tape.points[(i + 1) % n]);
        let lo = Point2::new(a.x.min(b.x), a.y.min(b.y));
        let hi = Point2::new(a.x.max(b.x), a.y.max(b.y));
        let (x0, y0, x1, y1) = grid.cells_near(lo, hi, reach);
        let (dx, dy) = (b.x - a.x, b.y - a.y);
        let len2 = (dx * dx + dy * dy).max(1e-18);
        let start = i as f64 * tape.step;
        for cy in y0..y1 {
            for cx in x0..x1 {
                let mut bits = 0u16;
                for k in 0..SUB * SUB {
                    let q = grid.subsample(cx, cy, k);
                    // Nearest point of the segment: the clamped projection.
                    let f = (((q.x - a.x) * dx + (q.y - a.y) * dy) / len2).clamp(0.0, 1.0);
                    let d2 = (q.x - a.x - f * dx).powi(2) + (q.y - a.y - f * dy).powi(2);
                    if d2 > tape.half_width * tape.half_width {
                        continue;
                    }
                    let on = tape
                        .dash
                        .is_none_or(|d| (start + f * tape.step).rem_euclid(2.0 * d) < d);
                    if on {
                        bits |= 1 << k;
                    }
                }
                mask[cy * grid.width + cx] |= bits;
            }
        }
    }
}

/// Sets the bits of the subsamples inside the convex `polygon`.
fn paint_polygon(grid: &Grid, mask: &mut [u16], polygon: &[Point2]) {
    if polygon.len() < 3 {
        return;
    }
    let lo = polygon
        .iter()
        .fold(Point2::new(f64::MAX, f64::MAX), |m, p| {
            Point2::new(m.x.min(p.x), m.y.min(p.y))
        });
    let hi = polygon
        .iter()
        .fold(Point2::new(f64::MIN, f64::MIN), |m, p| {
            Point2::new(m.x.max(p.x), m.y.max(p.y))
        });
    // Inside a convex polygon: on the same side of every edge (the sign of each cross).
    let side = |q: Point2, i: usize| {
        let (a, b) = (polygon[i], polygon[(i + 1) % polygon.len()]);
        (b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x)
    };
    let (x0, y0, x1, y1) = grid.cells_near(lo, hi, 0.0);
    for cy in y0..y1 {
        for cx in x0..x1 {
            let mut bits = 0u16;
            for k in 0..SUB * SUB {
                let q = grid.subsample(cx, cy, k);
                let signs = (0..polygon.len()).map(|i| side(q, i));
                let (mut pos, mut neg) = (false, false);
                for s in signs {
                    pos |= s > 0.0;
                    neg |= s < 0.0;
                }
                if !(pos && neg) {
                    bits |= 1 << k;
                }
            }
            mask[cy * grid.width + cx] |= bits;
        }
    }
}
