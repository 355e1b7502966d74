//! Path smoothing (seed 004 section A): a cubic (k = 3) B-spline, C2 continuous, sampled
//! densely with heading and signed curvature from its analytic derivatives.
//!
//! The polyline is densified (a control point every `control_spacing`, each vertex kept) and
//! used as the control polygon of a clamped uniform cubic B-spline: the curve starts at the
//! start, ends at the goal, follows straight stretches exactly and rounds each corner only
//! within a couple of control spacings of it.

use super::astar::SearchOptions;
use super::bspline::BSpline;
use super::segment_cells::for_each_cell;
use crate::geometry::{Point2, wrap_angle};
use crate::map::costmap::Costmap;

/// One sample of a smoothed path.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PathSample {
    pub position: Point2,
    /// Direction of travel, radians.
    pub heading: f64,
    /// Signed curvature, 1/m (positive turns left).
    pub curvature: f64,
}

/// How the samples of a smoothed path were made.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Smoothing {
    /// Not asked for: the polyline itself.
    Off,
    /// A B-spline with control points this far apart, metres.
    Spline { control_spacing: f64 },
    /// Every spline tried cut into costlier cells: the polyline (seed 004's fallback).
    Linear,
}

/// Samples of a cubic B-spline over `points`, about `sample_spacing` apart. Seed 004's edge
/// cases: one point gives itself with zero curvature, two points a straight line.
pub fn smooth(points: &[Point2], control_spacing: f64, sample_spacing: f64) -> Vec<PathSample> {
    let mut points = points.to_vec();
    points.dedup();
    if points.len() <= 2 {
        return linear(&points, sample_spacing);
    }
    // A cubic needs four control points: split every segment in two if there are fewer.
    let min_parts = if points.len() < 4 { 2 } else { 1 };
    let mut control = vec![[points[0].x, points[0].y]];
    for w in points.windows(2) {
        // Segments shorter than the spacing stay whole: extra points on the chords of a finely
        // sampled curve would make the control polygon, and so the curvature, wave.
        let parts = ((w[0].distance(w[1]) / control_spacing).ceil() as usize).max(min_parts);
        for k in 1..=parts {
            let f = k as f64 / parts as f64;
            control.push([
                w[0].x + f * (w[1].x - w[0].x),
                w[0].y + f * (w[1].y - w[0].y),
            ]);
        }
    }
    let spline = BSpline::clamped(3, control);
    let d1 = spline.derivative();
    let d2 = d1.derivative();
    let (lo, hi) = spline.domain();
    let count = (polyline_length(&points) / sample_spacing).ceil().max(1.0) as usize + 1;
    let mut out: Vec<PathSample> = (0..count)
        .map(|i| {
            let u = lo + (hi - lo) * i as f64 / (count - 1) as f64;
            let ([x, y], [dx, dy], [ddx, ddy]) = (spline.eval(u), d1.eval(u), d2.eval(u));
            let speed2 = dx * dx + dy * dy;
            // Seed 004 section A: kappa = (x'y'' - y'x'') / (x'^2 + y'^2)^(3/2).
            let curvature = if speed2 > 1e-18 {
                (dx * ddy - dy * ddx) / speed2.powf(1.5)
            } else {
                0.0
            };
            PathSample {
                position: Point2::new(x, y),
                heading: dy.atan2(dx),
                curvature,
            }
        })
        .collect();
    // Clamped knots interpolate the end controls; pin them against rounding.
    out[0].position = points[0];
    out[count - 1].position = points[points.len() - 1];
    out
}

/// The polyline itself, sampled about `sample_spacing` apart. Curvature is zero along the
/// segments; at a vertex it is the turn over one sample spacing (the discrete curvature
/// Δheading / Δs), so a velocity profile slows for the corner.
pub fn linear(points: &[Point2], sample_spacing: f64) -> Vec<PathSample> {
    let mut points = points.to_vec();
    points.dedup();
    let Some(&first) = points.first() else {
        return vec![];
    };
    let heading = |a: Point2, b: Point2| (b.y - a.y).atan2(b.x - a.x);
    let mut out = vec![PathSample {
        position: first,
        heading: points.get(1).map_or(0.0, |&b| heading(first, b)),
        curvature: 0.0,
    }];
    for (i, w) in points.windows(2).enumerate() {
        let h = heading(w[0], w[1]);
        let parts = (w[0].distance(w[1]) / sample_spacing).ceil().max(1.0) as usize;
        for k in 1..=parts {
            let f = k as f64 / parts as f64;
            let mut sample = PathSample {
                position: Point2::new(
                    w[0].x + f * (w[1].x - w[0].x),
                    w[0].y + f * (w[1].y - w[0].y),
                ),
                heading: h,
                curvature: 0.0,
            };
            if k == parts {
                sample.position = w[1];
                if let Some(&next) = points.get(i + 2) {
                    let turn = wrap_angle(heading(w[1], next) - h);
                    sample.curvature = turn / sample_spacing;
                }
            }
            out.push(sample);
        }
    }
    out
}

/// Smooths `points` and checks every sample on `map`: no sample may stand in a cell that may
/// not be entered, nor in one costlier than the worst cell the polyline touches (the start
/// cell is exempt: the robot is there). On a violation the control spacing is halved, up to
/// three times, which pulls the curve towards the corners; if that still fails the polyline
/// itself is returned ([`Smoothing::Linear`], seed 004's piecewise-linear fallback).
pub fn smooth_checked(
    points: &[Point2],
    map: &Costmap,
    options: &SearchOptions,
    control_spacing: f64,
    sample_spacing: f64,
) -> (Vec<PathSample>, Smoothing) {
    let start_cell = points.first().and_then(|&p| map.cell_of(p));
    let cost_at = |x: usize, y: usize| options.traversal_cost(map.get(x, y));
    // The worst enterable cell the polyline touches. Its segments may graze a blocked cell
    // (a diagonal step past an obstacle's corner): samples are kept out of those anyway.
    let mut worst = 0u8;
    for w in points.windows(2) {
        for_each_cell(map, w[0], w[1], |x, y| {
            if Some((x, y)) != start_cell {
                worst = worst.max(cost_at(x, y).unwrap_or(0));
            }
            true
        });
    }
    let acceptable = |samples: &[PathSample]| {
        samples.iter().all(|s| match map.cell_of(s.position) {
            Some(cell) if Some(cell) == start_cell => true,
            Some((x, y)) => cost_at(x, y).is_some_and(|c| c <= worst),
            None => false,
        })
    };
    let mut spacing = control_spacing;
    for _ in 0..4 {
        let samples = smooth(points, spacing, sample_spacing);
        if acceptable(&samples) {
            return (
                samples,
                Smoothing::Spline {
                    control_spacing: spacing,
                },
            );
        }
        spacing /= 2.0;
    }
    (linear(points, sample_spacing), Smoothing::Linear)
}

/// Total length of a polyline, metres.
pub fn polyline_length(points: &[Point2]) -> f64 {
    points.windows(2).map(|w| w[0].distance(w[1])).sum()
}
