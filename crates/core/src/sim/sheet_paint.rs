//! Paints a marker's printed sheet into a frame through a homography, as a camera's
//! sensor sees it: each frame pixel holds the mean of `s` x `s` samples spread evenly over
//! its area, each sample the sheet's grey there, interpolated bilinearly between the
//! sheet's pixels; a sample off the sheet sees what was drawn in the frame before.
//!
//! Most pixels of a large sheet lie inside one of its cells, where the sheet is one grey:
//! such a pixel is given that grey without sampling, which is exactly what sampling gives.
//! The sheet is sampled only along the edges between cells of different colour.

#[cfg(test)]
mod tests;

use crate::perception::region::Region;

/// A lit marker sheet ready to paint: square, `side` pixels across.
#[derive(Clone, Debug)]
pub struct Sheet {
    side: usize,
    pixels: Vec<u8>,
    /// Summed-area table over the sheet's 2 x 2 blocks (block (x, y) holds pixels x..=x+1,
    /// y..=y+1), counting the blocks that are not one grey: entry (x, y) counts those
    /// left of column x and above row y, `side` entries a row.
    mixed: Vec<u32>,
}

impl Sheet {
    /// A sheet of `side` x `side` pixels, rows top to bottom.
    pub fn new(side: usize, pixels: Vec<u8>) -> Self {
        assert!(side >= 2 && pixels.len() == side * side, "a square sheet");
        let at = |x: usize, y: usize| pixels[y * side + x];
        let mut mixed = vec![0u32; side * side];
        for y in 0..side - 1 {
            for x in 0..side - 1 {
                let p = at(x, y);
                let flat = at(x + 1, y) == p && at(x, y + 1) == p && at(x + 1, y + 1) == p;
                mixed[(y + 1) * side + x + 1] =
                    u32::from(!flat) + mixed[y * side + x + 1] + mixed[(y + 1) * side + x]
                        - mixed[y * side + x];
            }
        }
        Self {
            side,
            pixels,
            mixed,
        }
    }

    /// Pixels across.
    pub fn side(&self) -> usize {
        self.side
    }

    /// Grey levels, rows top to bottom.
    pub fn pixels(&self) -> &[u8] {
        &self.pixels
    }

    /// Mixed blocks among blocks x0..=x1 by y0..=y1 (all inside the sheet): four corners
    /// of the summed-area table (Crow, "Summed-area tables for texture mapping", 1984).
    fn mixed_blocks(&self, x0: usize, y0: usize, x1: usize, y1: usize) -> u32 {
        let n = self.side;
        self.mixed[(y1 + 1) * n + x1 + 1] + self.mixed[y0 * n + x0]
            - self.mixed[y0 * n + x1 + 1]
            - self.mixed[(y1 + 1) * n + x0]
    }

    /// The sheet's grey at (qu, qv) / `STEPS` in pixel-centre coordinates, interpolated
    /// bilinearly, in `1 / STEPS^2` grey levels; `None` off the sheet (where OpenCV's
    /// `warpPerspective` leaves a transparent border).
    #[inline]
    fn sample(&self, qu: i64, qv: i64) -> Option<u32> {
        let last = ((self.side - 1) * STEPS) as i64;
        if !((0..last).contains(&qu) && (0..last).contains(&qv)) {
            return None;
        }
        let (qu, qv) = (qu as usize, qv as usize);
        let (x, y) = (qu / STEPS, qv / STEPS);
        let (fx, fy) = ((qu % STEPS) as u32, (qv % STEPS) as u32);
        let i = y * self.side + x;
        let p = |k: usize| u32::from(self.pixels[k]);
        let one = STEPS as u32;
        // Bilinear interpolation in whole 1/STEPS weights, as OpenCV's fixed-point remap.
        let top = p(i) * (one - fx) + p(i + 1) * fx;
        let bottom = p(i + self.side) * (one - fx) + p(i + self.side + 1) * fx;
        Some(top * (one - fy) + bottom * fy)
    }
}

/// Sample positions are taken to the nearest 1/32 of a sheet pixel, as OpenCV's warps
/// take them (`INTER_TAB_SIZE`).
const STEPS: usize = 32;
/// How far that moves a sample at most, sheet pixels, with room for rounding.
const SNAP: f64 = 0.5 / STEPS as f64 + 1e-9;

/// `x` rounded to the nearest whole number, halves to even (as `round_ties_even`, but
/// without a library call): the sum with 1.5 * 2^52 has no fraction bits, so the addition
/// rounds x to a whole number, ties to even (IEEE 754-2008 4.3.1), and its bits count up
/// from those of 1.5 * 2^52 one to a unit. Exact for |x| < 2^51.
#[inline]
fn nearest(x: f64) -> i64 {
    const SHIFT: f64 = 6_755_399_441_055_744.0;
    (x + SHIFT).to_bits() as i64 - SHIFT.to_bits() as i64
}

/// A homography as a row-major 3 x 3 matrix: (x, y) -> (h0 x + h1 y + h2, h3 x + h4 y + h5)
/// / (h6 x + h7 y + h8) (Hartley & Zisserman 2.3).
pub type Homography = [f64; 9];

/// `h` scaled so that its denominator is positive at frame point (x, y), a point of the
/// sheet's image: a homography is the same map at any scale, and `map` takes a point with
/// a denominator of the other sign to look at the sheet's plane from behind.
pub fn facing(h: Homography, x: f64, y: f64) -> Homography {
    if h[6] * x + h[7] * y + h[8] < 0.0 {
        h.map(|v| -v)
    } else {
        h
    }
}

/// Where frame point (x, y) falls on the sheet, or `None` when it looks at the sheet's
/// plane from behind (the denominator is not positive; see `facing`).
#[inline]
fn map(h: &Homography, x: f64, y: f64) -> Option<(f64, f64)> {
    let w = h[6] * x + h[7] * y + h[8];
    (w > 0.0).then(|| {
        let r = 1.0 / w;
        (
            (h[0] * x + h[1] * y + h[2]) * r,
            (h[3] * x + h[4] * y + h[5]) * r,
        )
    })
}

/// Pixels along each side of the tiles a paint is worked in: a tile the sheet misses, or
/// that lies inside one of its cells, is done in one step.
const TILE: usize = 8;

/// What a patch of the frame shows of the sheet.
enum Cover {
    /// Nothing: every sample is off the sheet.
    Off,
    /// One grey under every sample.
    Flat(u8),
    /// Something else, or it cannot be told from the patch's corners.
    Mixed,
}

/// Paints `sheet` into the pixels `bounds` of `frame` (`width` pixels a row): frame pixel
/// centres are whole numbers, `to_sheet` takes frame points to sheet points (pixel
/// centres whole numbers too), and every pixel is the mean of `s` x `s` samples.
pub fn paint(
    frame: &mut [u8],
    width: usize,
    bounds: Region,
    sheet: &Sheet,
    to_sheet: &Homography,
    s: usize,
) {
    let s = s.max(1);
    for ty in (bounds.y0..bounds.y1).step_by(TILE) {
        for tx in (bounds.x0..bounds.x1).step_by(TILE) {
            let tile = Region {
                x0: tx,
                y0: ty,
                x1: (tx + TILE).min(bounds.x1),
                y1: (ty + TILE).min(bounds.y1),
            };
            match cover(sheet, to_sheet, &tile) {
                Cover::Off => {}
                Cover::Flat(grey) => {
                    for y in tile.y0..tile.y1 {
                        frame[y * width + tile.x0..y * width + tile.x1].fill(grey);
                    }
                }
                Cover::Mixed => paint_pixels(frame, width, &tile, sheet, to_sheet, s),
            }
        }
    }
}

/// Paints the pixels of `tile` one by one.
fn paint_pixels(
    frame: &mut [u8],
    width: usize,
    tile: &Region,
    sheet: &Sheet,
    to_sheet: &Homography,
    s: usize,
) {
    // Where the pixel corners fall, (TILE + 1) a row.
    let mut grid = [None; (TILE + 1) * (TILE + 1)];
    for (j, y) in (tile.y0..=tile.y1).enumerate() {
        for (i, x) in (tile.x0..=tile.x1).enumerate() {
            grid[j * (TILE + 1) + i] = map(to_sheet, x as f64 - 0.5, y as f64 - 0.5);
        }
    }
    for (j, y) in (tile.y0..tile.y1).enumerate() {
        for (i, x) in (tile.x0..tile.x1).enumerate() {
            let k = j * (TILE + 1) + i;
            let corners = [grid[k], grid[k + 1], grid[k + TILE + 1], grid[k + TILE + 2]];
            let p = &mut frame[y * width + x];
            match cover_of(sheet, corners) {
                Cover::Off => {}
                Cover::Flat(grey) => *p = grey,
                Cover::Mixed => *p = sampled(*p, x, y, sheet, to_sheet, s),
            }
        }
    }
}

/// What the pixels `patch` show of the sheet, told from where the patch's outer corners
/// fall: when the sheet's plane is in front of all four, the image of the patch is the
/// convex quad they span, and every sample lies inside its bounding box.
fn cover(sheet: &Sheet, to_sheet: &Homography, patch: &Region) -> Cover {
    let (x0, y0) = (patch.x0 as f64 - 0.5, patch.y0 as f64 - 0.5);
    let (x1, y1) = (patch.x1 as f64 - 0.5, patch.y1 as f64 - 0.5);
    cover_of(
        sheet,
        [(x0, y0), (x1, y0), (x0, y1), (x1, y1)].map(|(x, y)| map(to_sheet, x, y)),
    )
}

/// `cover` from where the patch's corners fall on the sheet (none: seen from behind).
#[inline(always)]
fn cover_of(sheet: &Sheet, corners: [Option<(f64, f64)>; 4]) -> Cover {
    let [Some(a), Some(b), Some(c), Some(d)] = corners else {
        return Cover::Mixed;
    };
    // Samples may snap a little way out of the quad's bounding box.
    let (u0, u1) = (
        a.0.min(b.0).min(c.0).min(d.0) - SNAP,
        a.0.max(b.0).max(c.0).max(d.0) + SNAP,
    );
    let (v0, v1) = (
        a.1.min(b.1).min(c.1).min(d.1) - SNAP,
        a.1.max(b.1).max(c.1).max(d.1) + SNAP,
    );
    let last = (sheet.side - 1) as f64;
    if u1 < 0.0 || v1 < 0.0 || u0 >= last || v0 >= last {
        return Cover::Off;
    }
    if !(u0 >= 0.0 && v0 >= 0.0 && u1 < last && v1 < last) {
        return Cover::Mixed;
    }
    // Blocks under the samples: all inside the sheet, and none of two greys.
    let (bx0, by0, bx1, by1) = (u0 as usize, v0 as usize, u1 as usize, v1 as usize);
    if sheet.mixed_blocks(bx0, by0, bx1, by1) == 0 {
        Cover::Flat(sheet.pixels[by0 * sheet.side + bx0])
    } else {
        Cover::Mixed
    }
}

/// The mean of the `s` x `s` samples of pixel (px, py) whose grey is `old` before painting:
/// sample (i, j) at (px + (i + 1/2) / s - 1/2, py + (j + 1/2) / s - 1/2).
fn sampled(old: u8, px: usize, py: usize, sheet: &Sheet, to_sheet: &Homography, s: usize) -> u8 {
    // Numerators scaled by STEPS (a power of two, so exactly) give positions in 1/STEPS.
    let k = STEPS as f64;
    let h = &[
        to_sheet[0] * k,
        to_sheet[1] * k,
        to_sheet[2] * k,
        to_sheet[3] * k,
        to_sheet[4] * k,
        to_sheet[5] * k,
        to_sheet[6],
        to_sheet[7],
        to_sheet[8],
    ];
    let step = 1.0 / s as f64;
    let first = step / 2.0 - 0.5;
    let x = px as f64 + first;
    // Greys in 1 / STEPS^2 of a level, as `Sheet::sample` gives them.
    let unit = (STEPS * STEPS) as u32;
    let old = u32::from(old) * unit;
    let mut sum = 0u32;
    for j in 0..s {
        let y = py as f64 + first + j as f64 * step;
        // Along a row of samples the homography's three terms grow by fixed steps.
        let (mut u, mut v, mut w) = (
            h[0] * x + h[1] * y + h[2],
            h[3] * x + h[4] * y + h[5],
            h[6] * x + h[7] * y + h[8],
        );
        for _ in 0..s {
            sum += if w > 0.0 {
                let r = 1.0 / w;
                sheet.sample(nearest(u * r), nearest(v * r)).unwrap_or(old)
            } else {
                old
            };
            u += h[0] * step;
            v += h[3] * step;
            w += h[6] * step;
        }
    }
    // The mean, rounded half up.
    let count = (s * s) as u32 * unit;
    ((sum + count / 2) / count).min(255) as u8
}
