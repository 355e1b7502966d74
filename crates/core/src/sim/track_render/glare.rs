//! Glare (seed 000 §2.1.3: ceiling lighting reflects off the floor; §6.4.2's lighting
//! tests): ceiling lamps on a grid placed once from the renderer's seed, whose mirror
//! images on the floor move as the robot does. Along one image row the floor points fall
//! at even steps (`floor`), so the pixels of a row inside a spot's ellipse are found by
//! solving a quadratic for the stretch, and only those pixels are worked on.

use super::floor::{EVEN, FloorRays};
use super::scanline::FloorLine;
use super::view::View;
use crate::geometry::{Point2, Pose2};
use nalgebra::Vector3;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

/// Spacing of the ceiling lamps' grid, metres.
const LAMP_SPACING: f64 = 1.5;
/// The chance that a fitting of the grid is lit: with every one lit, their mirror images
/// (shrunk by h / (h + H), 1.5 m apart becomes 8.5 cm) would crowd the near floor.
const LIT_FITTINGS: f64 = 0.5;
/// Height of the ceiling lamps, metres.
const LAMP_HEIGHT: f64 = 2.5;
/// A ceiling lamp's radius (diffuser panels 0.6 to 1 m across), metres.
const LAMP_RADIUS: (f64, f64) = (0.3, 0.5);
/// How far the floor's roughness spreads a reflection past the lamp's mirror image, metres.
const ROUGHNESS_SPREAD: f64 = 0.012;
/// How much longer a spot is along the line of sight than across it: a mirror image on a
/// slightly rough floor is drawn out towards the viewer.
const SPOT_ELONGATION: f64 = 1.4;
/// The fraction of a spot's radius that is fully bright; it fades out beyond.
const SPOT_CORE: f64 = 0.45;
const CORE: f32 = SPOT_CORE as f32;
/// Seed 000 §2.1.3: direct fluorescent reflections have V 245 +- 8.
const GLARE_VALUE: (f64, f64) = (245.0, 8.0);
/// The reflections' colour less than their value in blue and green: a warm white of
/// saturation under 10 (seed 000 §2.1.3: reflections have chroma 2 of 14).
const GLARE_TINT: [f64; 3] = [7.0, 3.0, 0.0];

/// How far single precision may put a floor point off where double precision does, metres.
const SINGLE_SLACK: f64 = 1e-5;
/// Image rows painted as one piece of work when the frame is shared among the cores.
const BAND_ROWS: usize = 16;

/// A ceiling lamp: where it hangs, its size and the brightness of its reflection.
#[derive(Clone, Debug)]
struct Lamp {
    at: Point2,
    radius: f64,
    bgr: [f64; 3],
}

/// The ceiling lamps over the floor.
#[derive(Clone, Debug)]
pub struct Ceiling {
    lamps: Vec<Lamp>,
}

impl Ceiling {
    /// Lamps every `LAMP_SPACING` over `lo`-`hi` and a spacing round it, the grid offset
    /// by the seed.
    pub fn new(rng: &mut ChaCha8Rng, lo: Point2, hi: Point2) -> Self {
        let offset = (
            rng.random_range(0.0..LAMP_SPACING),
            rng.random_range(0.0..LAMP_SPACING),
        );
        let cols = ((hi.x - lo.x) / LAMP_SPACING).ceil() as i64 + 2;
        let rows = ((hi.y - lo.y) / LAMP_SPACING).ceil() as i64 + 2;
        let mut lamps = Vec::new();
        for j in -1..rows {
            for i in -1..cols {
                let at = Point2::new(
                    lo.x + offset.0 + i as f64 * LAMP_SPACING,
                    lo.y + offset.1 + j as f64 * LAMP_SPACING,
                );
                let lit = rng.random_bool(LIT_FITTINGS);
                let radius = rng.random_range(LAMP_RADIUS.0..LAMP_RADIUS.1);
                let (mean, spread) = GLARE_VALUE;
                let value = rng.random_range(mean - spread * 0.75..mean + spread * 0.75);
                if !lit {
                    continue;
                }
                lamps.push(Lamp {
                    at,
                    radius,
                    bgr: GLARE_TINT.map(|t| value - t),
                });
            }
        }
        Self { lamps }
    }

    /// Paints the lamps' reflections over the floor pixels of `out` seen through `view`,
    /// lamp after lamp in each pixel.
    pub fn paint_glare(&self, rays: &FloorRays, view: &View, pose: Pose2, out: &mut [u8]) {
        let spots: Vec<Spot> = (self.lamps.iter())
            .filter_map(|lamp| Spot::of(lamp, view, pose))
            .collect();
        let (Some(y0), Some(y1)) = (
            spots.iter().map(|s| s.rows.0).min(),
            spots.iter().map(|s| s.rows.1).max(),
        ) else {
            return;
        };
        let width = view.width;
        // Rows are shared among the cores; each pixel is worked on its own, so the frame
        // is the same however many there are.
        let bands = out[3 * y0 * width..3 * y1 * width].par_chunks_mut(3 * width * BAND_ROWS);
        bands.enumerate().for_each(|(band, rows)| {
            let mut scratch = (Vec::new(), Vec::new());
            for (k, row) in rows.chunks_mut(3 * width).enumerate() {
                let y = y0 + band * BAND_ROWS + k;
                for spot in spots.iter().filter(|s| (s.rows.0..s.rows.1).contains(&y)) {
                    for (start, end, line) in rays.floor_stretches(y) {
                        let (lo, hi) = (start.max(spot.cols.0), end.min(spot.cols.1));
                        let xs = spot.crossing(start, &line, lo, hi);
                        spot.paint_stretch(rays, y * width, xs, row, &mut scratch);
                    }
                }
            }
        });
    }
}

/// One lamp's reflection seen from a pose: the image box it can cover and its ellipse on
/// the floor, relative to the robot's floor points.
struct Spot {
    /// Image rows and columns, half-open.
    rows: (usize, usize),
    cols: (usize, usize),
    /// The pose less the spot's centre, and the pose's heading's sine and cosine.
    offset: [f32; 2],
    sin_cos: [f32; 2],
    /// The ellipse's axes, each divided by its radius: along the line of sight, across it.
    along: [f32; 2],
    across: [f32; 2],
    glare: [f32; 3],
    /// How far, in ellipse radii, a floor point may lie off its stretch's even steps.
    slack: f64,
}

impl Spot {
    fn of(lamp: &Lamp, view: &View, pose: Pose2) -> Option<Self> {
        let (s, c) = pose.theta.sin_cos();
        let under_lens = Point2::new(view.lens.x, view.lens.y);
        let h = view.lens.z;
        // Law of reflection: the mirror path from the lens (height h) to the lamp (height
        // H) meets the floor h / (h + H) of the way between their feet.
        let f = h / (h + LAMP_HEIGHT);
        let spot = Point2::new(
            under_lens.x + f * (lamp.at.x - under_lens.x),
            under_lens.y + f * (lamp.at.y - under_lens.y),
        );
        let toward = (spot.x - under_lens.x, spot.y - under_lens.y);
        let norm = toward.0.hypot(toward.1);
        let (ax, ay) = if norm > 1e-9 {
            (toward.0 / norm, toward.1 / norm)
        } else {
            (c, s)
        };
        // The mirror image shrinks the lamp by the same h / (h + H) (similar triangles),
        // and roughness spreads it a little.
        let radius = lamp.radius * f + ROUGHNESS_SPREAD;
        let (along, across) = (radius * SPOT_ELONGATION, radius);
        let (x0, y0, x1, y1) = spot_box(view, spot, (ax, ay), along, across)?;
        // In single precision, relative to the spot: the floor point of pixel i is
        // pose + Rz(theta) ray, so its offset from the spot is (pose - spot) + Rz ray.
        Some(Self {
            rows: (y0, y1),
            cols: (x0, x1),
            offset: [(pose.x - spot.x) as f32, (pose.y - spot.y) as f32],
            sin_cos: [s as f32, c as f32],
            along: [(ax / along) as f32, (ay / along) as f32],
            // The axis across the line of sight.
            across: [(-ay / across) as f32, (ax / across) as f32],
            glare: lamp.bgr.map(|v| v as f32),
            slack: (EVEN + SINGLE_SLACK) / across,
        })
    }

    /// The columns of `lo..hi`, in the stretch beginning at column `start` along `line`
    /// (robot frame), that may fall inside the ellipse: a few more than do.
    fn crossing(
        &self,
        start: usize,
        line: &FloorLine,
        lo: usize,
        hi: usize,
    ) -> std::ops::Range<usize> {
        if lo >= hi {
            return lo..lo;
        }
        let [s, c] = self.sin_cos.map(f64::from);
        let [ox, oy] = self.offset.map(f64::from);
        let turn = |[x, y]: [f64; 2]| [c * x - s * y, s * x + c * y];
        let dot = |p: [f64; 2], a: [f32; 2]| p[0] * f64::from(a[0]) + p[1] * f64::from(a[1]);
        let [px, py] = turn(line.start);
        let first = [ox + px, oy + py];
        let step = turn(line.step);
        // Pixel start + k is in the ellipse where (a0 + k da)^2 + (b0 + k db)^2 < r^2.
        let (a0, da) = (dot(first, self.along), dot(step, self.along));
        let (b0, db) = (dot(first, self.across), dot(step, self.across));
        let r = 1.0 + self.slack;
        let qa = da * da + db * db;
        let qb = a0 * da + b0 * db;
        let qc = a0 * a0 + b0 * b0 - r * r;
        if qa < 1e-18 {
            return if qc < 0.0 { lo..hi } else { lo..lo };
        }
        let disc = qb * qb - qa * qc;
        if disc < 0.0 {
            return lo..lo;
        }
        let root = disc.sqrt();
        let (k1, k2) = ((-qb - root) / qa, (-qb + root) / qa);
        let column = |k: f64| (start as f64 + k).clamp(lo as f64, hi as f64) as usize;
        let (first, last) = (column((k1 - 1.0).floor()), column((k2 + 2.0).ceil()));
        first..last.max(first)
    }

    /// Blends the glare into pixels `xs` of `row` (its first pixel is pixel `first` of
    /// the frame): every pixel's weight first, then every byte blended alike, a loop the
    /// compiler can vectorise (a pixel of weight 0 keeps its bytes exactly).
    fn paint_stretch(
        &self,
        rays: &FloorRays,
        first: usize,
        xs: std::ops::Range<usize>,
        row: &mut [u8],
        (weights, tints): &mut (Vec<f32>, Vec<f32>),
    ) {
        weights.clear();
        tints.clear();
        for x in xs.clone() {
            let w = rays.point(first + x).map_or(0.0, |p| self.weight(p));
            weights.extend([w; 3]);
            tints.extend(self.glare);
        }
        let bytes = &mut row[3 * xs.start..3 * xs.end];
        for ((byte, &w), &glare) in bytes.iter_mut().zip(weights.iter()).zip(tints.iter()) {
            let v = f32::from(*byte) * (1.0 - w) + glare * w;
            *byte = (v + 0.5).clamp(0.0, 255.0) as u8;
        }
    }

    /// The glare's share of the pixel whose floor point is `[rx, ry]` (robot frame): full
    /// within the core, then a smoothstep fade to the rim, none outside the ellipse.
    #[inline]
    fn weight(&self, [rx, ry]: [f32; 2]) -> f32 {
        let ([ox, oy], [sin, cos]) = (self.offset, self.sin_cos);
        let ([ax, ay], [bx, by]) = (self.along, self.across);
        let wx = ox + cos * rx - sin * ry;
        let wy = oy + sin * rx + cos * ry;
        let a = wx * ax + wy * ay;
        let b = wx * bx + wy * by;
        let d2 = a * a + b * b;
        if d2 >= 1.0 {
            return 0.0;
        }
        let t = ((d2.sqrt() - CORE) / (1.0 - CORE)).clamp(0.0, 1.0);
        1.0 - t * t * (3.0 - 2.0 * t)
    }
}

/// The image rows and columns (half-open) that an elliptic spot can cover, None when it
/// is wholly behind the lens or outside the image.
fn spot_box(
    view: &View,
    spot: Point2,
    axis: (f64, f64),
    along: f64,
    across: f64,
) -> Option<(usize, usize, usize, usize)> {
    let (mut u0, mut v0, mut u1, mut v1) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
    let mut behind = false;
    for k in 0..16 {
        let a = k as f64 * std::f64::consts::TAU / 16.0;
        // A circumscribing polygon: the ellipse's points pushed out by 1 / cos(pi / 16).
        let (ea, eb) = (a.cos() * along * 1.02, a.sin() * across * 1.02);
        let p = Vector3::new(
            spot.x + ea * axis.0 - eb * axis.1,
            spot.y + ea * axis.1 + eb * axis.0,
            0.0,
        );
        match view.pixel(p) {
            Some((u, v)) => {
                u0 = u0.min(u);
                v0 = v0.min(v);
                u1 = u1.max(u);
                v1 = v1.max(v);
            }
            None => behind = true,
        }
    }
    if u0 > u1 {
        return None;
    }
    let (w, h) = (view.width as f64, view.height as f64);
    if behind {
        // Part of the spot is behind the lens: it may reach any column of the bottom rows.
        (u0, u1, v1) = (0.0, w, h);
    }
    let clampi = |x: f64, max: f64| x.clamp(0.0, max) as usize;
    let (x0, x1) = (clampi(u0.floor(), w), clampi(u1.ceil() + 1.0, w));
    let (y0, y1) = (clampi(v0.floor(), h), clampi(v1.ceil() + 1.0, h));
    (x0 < x1 && y0 < y1).then_some((x0, y0, x1, y1))
}

#[cfg(test)]
#[path = "glare_tests.rs"]
mod tests;
