//! The shape of a generated lane track: the control polygon of its closed cubic B-spline
//! centreline, either a rounded rectangle (points along a rectangle's sides, so the lane
//! has straights) or a star (points at angles round the centre, their radii varied
//! smoothly), with one or two of its points (or pairs) pulled in for S-bends, stretched to fill the room
//! the walls leave.

use super::draw::tidy;
use crate::geometry::Point2;
use crate::sim::track::closed_bspline;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use std::f64::consts::TAU;

/// Control points round the centreline: fewer give long sweeping bends, more give
/// tighter and more varied ones.
const CONTROL_POINTS: (usize, usize) = (8, 16);
/// A rectangle's points are nudged along its sides by up to this fraction of their
/// spacing, so its corners round off with different radii.
const SIDE_JITTER: f64 = 0.35;
/// A star's points are nudged round by up to this fraction of their angular spacing.
const ANGLE_JITTER: f64 = 0.25;
/// Superellipse exponents of a star: 2 is an ellipse, 5 nearly a rectangle.
const SQUARENESS: (f64, f64) = (2.0, 5.0);
/// Largest amplitude of each of the 2nd and 3rd harmonics of a star's radius, as a
/// fraction of it.
const HARMONIC: f64 = 0.15;
/// A pulled-in control point keeps this fraction of its distance from the centre.
const DENTS: (f64, f64) = (0.3, 0.7);
/// The lane's bounding box fills this fraction of the room, each way.
const FILL: (f64, f64) = (0.85, 1.0);

/// The control points of a closed centreline inside the box `half_x` x `half_y` either
/// side of the centre, to the millimetre, in driving order.
pub fn control_points(rng: &mut ChaCha8Rng, half_x: f64, half_y: f64) -> Vec<[f64; 2]> {
    let n = rng.random_range(CONTROL_POINTS.0..=CONTROL_POINTS.1);
    let mut unit = if rng.random_bool(0.5) {
        rounded_rectangle(rng, n)
    } else {
        star(rng, n)
    };
    // S-bends: none in a quarter of tracks, one in half, two in a quarter.
    let dents = [0, 1, 1, 2][rng.random_range(0..4usize)];
    for _ in 0..dents {
        // One point, or two neighbours for a wider, deeper dent with gentler bends.
        let (first, width) = (rng.random_range(0..n), rng.random_range(1..=2usize));
        let keep = rng.random_range(DENTS.0..=DENTS.1);
        for k in (first..first + width).map(|k| k % n) {
            unit[k] = Point2::new(unit[k].x * keep, unit[k].y * keep);
        }
    }
    // Driven either way round: the posts on the right stand outside or inside the loop.
    if rng.random_bool(0.5) {
        unit.reverse();
    }
    fit(rng, &unit, half_x, half_y)
}

/// `n` points along the sides of the square [-1, 1]^2, evenly spaced from a random
/// start, each nudged along the perimeter: the spline runs straight past three or more
/// on one side and rounds the corners.
fn rounded_rectangle(rng: &mut ChaCha8Rng, n: usize) -> Vec<Point2> {
    const PERIMETER: f64 = 8.0;
    let spacing = PERIMETER / n as f64;
    let first = rng.random_range(0.0..PERIMETER);
    (0..n)
        .map(|k| {
            let nudge = rng.random_range(-SIDE_JITTER..=SIDE_JITTER);
            let s = (first + (k as f64 + nudge) * spacing).rem_euclid(PERIMETER);
            // Counter-clockwise from (-1, -1): bottom, right, top, left, 2 long each.
            match s {
                s if s < 2.0 => Point2::new(-1.0 + s, -1.0),
                s if s < 4.0 => Point2::new(1.0, -1.0 + (s - 2.0)),
                s if s < 6.0 => Point2::new(1.0 - (s - 4.0), 1.0),
                s => Point2::new(-1.0, 1.0 - (s - 6.0)),
            }
        })
        .collect()
}

/// `n` points at angles round the centre on a turned superellipse, their radii varied by
/// the 2nd and 3rd harmonics.
fn star(rng: &mut ChaCha8Rng, n: usize) -> Vec<Point2> {
    let squareness = rng.random_range(SQUARENESS.0..=SQUARENESS.1);
    let turn = rng.random_range(0.0..TAU);
    let harmonics: Vec<(f64, f64, f64)> = [2.0, 3.0]
        .into_iter()
        .map(|m| {
            (
                m,
                rng.random_range(0.0..HARMONIC),
                rng.random_range(0.0..TAU),
            )
        })
        .collect();
    (0..n)
        .map(|k| {
            let nudge = rng.random_range(-ANGLE_JITTER..ANGLE_JITTER);
            let a = (k as f64 + nudge) * TAU / n as f64;
            // Superellipse |x|^q + |y|^q = 1 in polar form (Lamé's curve):
            // r = (|cos a|^q + |sin a|^q)^(-1/q), in the frame turned by `turn`.
            let (st, ct) = (a - turn).sin_cos();
            let r = (ct.abs().powf(squareness) + st.abs().powf(squareness)).powf(-1.0 / squareness);
            // A Fourier series of the radius: r (1 + sum a_m cos(m a + phase_m)).
            let wobble: f64 = (harmonics.iter())
                .map(|&(m, amplitude, phase)| amplitude * (m * a + phase).cos())
                .sum();
            let (s, c) = a.sin_cos();
            Point2::new(r * (1.0 + wobble) * c, r * (1.0 + wobble) * s)
        })
        .collect()
}

/// `unit` stretched and shifted so its spline's bounding box fills a drawn fraction of
/// the box `half_x` x `half_y`, to the millimetre.
fn fit(rng: &mut ChaCha8Rng, unit: &[Point2], half_x: f64, half_y: f64) -> Vec<[f64; 2]> {
    // A B-spline is affine invariant (Piegl & Tiller, The NURBS Book, 3.2): stretching
    // the control points stretches the curve, so its bounding box maps onto the room.
    let curve = closed_bspline(unit);
    let (lo, hi) = curve.iter().fold(
        (
            Point2::new(f64::MAX, f64::MAX),
            Point2::new(f64::MIN, f64::MIN),
        ),
        |(lo, hi), p| {
            (
                Point2::new(lo.x.min(p.x), lo.y.min(p.y)),
                Point2::new(hi.x.max(p.x), hi.y.max(p.y)),
            )
        },
    );
    let (fill_x, fill_y) = (
        rng.random_range(FILL.0..=FILL.1),
        rng.random_range(FILL.0..=FILL.1),
    );
    let scale_x = 2.0 * half_x * fill_x / (hi.x - lo.x).max(1e-9);
    let scale_y = 2.0 * half_y * fill_y / (hi.y - lo.y).max(1e-9);
    // Centred, then shifted within the room the fill leaves.
    let shift_x = rng.random_range(-1.0..=1.0) * half_x * (1.0 - fill_x);
    let shift_y = rng.random_range(-1.0..=1.0) * half_y * (1.0 - fill_y);
    let (mid_x, mid_y) = ((lo.x + hi.x) / 2.0, (lo.y + hi.y) / 2.0);
    let mm = |v: f64| tidy((v * 1000.0).round() / 1000.0);
    (unit.iter())
        .map(|p| {
            [
                mm((p.x - mid_x) * scale_x + shift_x),
                mm((p.y - mid_y) * scale_y + shift_y),
            ]
        })
        .collect()
}
