//! Shadows and glare (seed 000 §2.1.1: "shadows from pillars or furniture partially
//! obscure lanes", and ceiling lighting reflects off the floor; §6.4.2's lighting tests).
//! Both are placed once from the renderer's seed: shadows as hard-edged polygons fixed on
//! the floor, some across the lane; ceiling lamps on a grid whose mirror images on the
//! floor move as the robot does.

use super::floor::FloorRays;
use super::view::View;
use crate::geometry::{Point2, Pose2};
use crate::sim::track::Track;
use nalgebra::Vector3;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

/// Shadows laid across the lane, and elsewhere on the floor.
const SHADOWS_ON_LANE: usize = 3;
const SHADOWS_ELSEWHERE: usize = 3;
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

/// Hard shadows: convex parallelograms, half of them centred on the lane.
pub fn shadows(rng: &mut ChaCha8Rng, track: &Track, lo: Point2, hi: Point2) -> Vec<Vec<Point2>> {
    (0..SHADOWS_ON_LANE + SHADOWS_ELSEWHERE)
        .map(|i| {
            let centre = if i < SHADOWS_ON_LANE {
                track.at(rng.random_range(0.0..track.length())).0
            } else {
                Point2::new(rng.random_range(lo.x..hi.x), rng.random_range(lo.y..hi.y))
            };
            let length = rng.random_range(0.3..0.9);
            let width = rng.random_range(0.12..0.4);
            let shear = rng.random_range(-0.4..0.4);
            let turn = rng.random_range(0.0..std::f64::consts::TAU);
            let pose = Pose2::new(centre.x, centre.y, turn);
            let (l, w) = (length / 2.0, width / 2.0);
            [
                (-l - shear * w, -w),
                (l - shear * w, -w),
                (l + shear * w, w),
                (-l + shear * w, w),
            ]
            .map(|(x, y)| pose.transform_point(Point2::new(x, y)))
            .to_vec()
        })
        .collect()
}

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

    /// Paints the lamps' reflections over the floor pixels of `out` seen through `view`.
    pub fn paint_glare(&self, rays: &FloorRays, view: &View, pose: Pose2, out: &mut [u8]) {
        let (s, c) = pose.theta.sin_cos();
        let under_lens = Point2::new(view.lens.x, view.lens.y);
        let h = view.lens.z;
        for lamp in &self.lamps {
            // Law of reflection: the mirror path from the lens (height h) to the lamp
            // (height H) meets the floor h / (h + H) of the way between their feet.
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
            // The mirror image shrinks the lamp by the same h / (h + H) (similar
            // triangles), and roughness spreads it a little.
            let radius = lamp.radius * f + ROUGHNESS_SPREAD;
            let (along, across) = (radius * SPOT_ELONGATION, radius);
            let Some((x0, y0, x1, y1)) = spot_box(view, spot, (ax, ay), along, across) else {
                continue;
            };
            // The axis across the line of sight.
            let ax_across = (-ay, ax);
            // In single precision, relative to the spot: the floor point of pixel i is
            // pose + Rz(theta) ray, so its offset from the spot is (pose - spot) + Rz ray.
            let (ox, oy) = ((pose.x - spot.x) as f32, (pose.y - spot.y) as f32);
            let (sin, cos) = (s as f32, c as f32);
            let glare = lamp.bgr.map(|v| v as f32);
            let (ax, ay) = ((ax / along) as f32, (ay / along) as f32);
            let (bx, by) = ((ax_across.0 / across) as f32, (ax_across.1 / across) as f32);
            // Rows are shared among the cores; each pixel is worked on its own, so the
            // frame is the same however many there are.
            let width = view.width;
            let rows = out[3 * y0 * width..3 * y1 * width].par_chunks_mut(3 * width);
            rows.enumerate().for_each(|(k, row)| {
                let y = y0 + k;
                for x in x0..x1 {
                    let Some([rx, ry]) = rays.point(y * width + x) else {
                        continue;
                    };
                    let wx = ox + cos * rx - sin * ry;
                    let wy = oy + sin * rx + cos * ry;
                    let a = wx * ax + wy * ay;
                    let b = wx * bx + wy * by;
                    let d2 = a * a + b * b;
                    if d2 >= 1.0 {
                        continue;
                    }
                    // Full within the core, then a smoothstep fade to the rim.
                    let t = ((d2.sqrt() - CORE) / (1.0 - CORE)).clamp(0.0, 1.0);
                    let w = 1.0 - t * t * (3.0 - 2.0 * t);
                    let px = &mut row[3 * x..3 * x + 3];
                    for (channel, glare) in px.iter_mut().zip(glare) {
                        let v = f32::from(*channel) * (1.0 - w) + glare * w;
                        *channel = (v + 0.5).clamp(0.0, 255.0) as u8;
                    }
                }
            });
        }
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
