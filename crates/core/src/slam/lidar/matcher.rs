//! Correlative scan matching (Olson, "Real-Time Correlative Scan Matching", ICRA 2009):
//! every pose of a window round the odometry's guess is scored by how well the scan's
//! points land on the likelihood field, first on a coarse copy of the field, then finely
//! round the best coarse poses, then refined between cells; the spread of good scores
//! round the best pose is the match's covariance (Olson 2009 section III-C; Karto's
//! ComputePositionalCovariance), which is what tells a corridor's ambiguity from a
//! corner's certainty.

use super::field::Field;
use crate::geometry::{Point2, Pose2, wrap_angle};
use nalgebra::Matrix3;

/// Where to search: half the window's width (m) and half its angle (rad).
#[derive(Clone, Copy, Debug)]
pub struct Window {
    pub half_width: f64,
    pub half_angle: f64,
}

/// The best pose found, its response (the mean of the points' likelihoods, 0 to 1) and
/// its covariance (x, y, θ).
#[derive(Clone, Copy, Debug)]
pub struct Match {
    pub pose: Pose2,
    pub response: f64,
    pub covariance: Matrix3<f64>,
}

impl Match {
    /// The position's standard deviation along its worst direction, metres.
    pub fn position_std(&self) -> f64 {
        let c = self.covariance.fixed_view::<2, 2>(0, 0).into_owned();
        crate::slam::ellipse::axes(&c, 1.0).0
    }
}

/// Coarse poses followed up finely.
const CANDIDATES: usize = 8;
/// Responses this far below the best still count in the covariance's spread, weighted
/// exp(-drop / SPREAD_SCALE).
const SPREAD_SCALE: f64 = 0.03;
/// Cells either side of the best pose sampled for the covariance.
const SPREAD_CELLS: i32 = 4;
/// The covariance never claims better than this: a standard deviation of a quarter cell
/// and of half an angular step.
const FLOOR_CELLS: f64 = 0.25;
/// Hill-climbing halvings of the step after the fine search.
const REFINE_LEVELS: usize = 3;

/// Matches `points` (robot frame) against `fine` (and `coarse`, its coarser copy) within
/// `window` of `guess`. `None` without points.
pub fn correlate(
    fine: &Field,
    coarse: &Field,
    points: &[Point2],
    guess: Pose2,
    window: Window,
) -> Option<Match> {
    if points.is_empty() {
        return None;
    }
    let reach = points.iter().map(|p| p.x.hypot(p.y)).fold(0.1, f64::max);
    // The farthest point moves one fine cell per angular step (Olson 2009 section IV).
    let fine_angle = (fine.resolution / reach).atan();
    let coarse_angle = 2.0 * fine_angle;
    let n = points.len() as f64;

    // Coarse pass: whole coarse cells and double angular steps over the window.
    let steps_xy = (window.half_width / coarse.resolution).round() as i32;
    let steps_a = (window.half_angle / coarse_angle).round() as i32;
    let mut best: Vec<(f64, Pose2)> = Vec::with_capacity(CANDIDATES + 1);
    let mut rotated = Vec::with_capacity(points.len());
    let mut cells = Vec::with_capacity(points.len());
    for ka in -steps_a..=steps_a {
        let theta = guess.theta + f64::from(ka) * coarse_angle;
        rotate(points, theta, &mut rotated);
        cells_of(coarse, &rotated, guess.x, guess.y, &mut cells);
        for ky in -steps_xy..=steps_xy {
            for kx in -steps_xy..=steps_xy {
                let score = score_shifted(coarse, &cells, kx, ky);
                let (x, y) = (
                    guess.x + f64::from(kx) * coarse.resolution,
                    guess.y + f64::from(ky) * coarse.resolution,
                );
                keep_best(&mut best, score, Pose2::new(x, y, theta));
            }
        }
    }

    // Fine pass round each coarse candidate: fine cells and angles within one coarse step.
    let mut top = (f64::NEG_INFINITY, guess);
    for &(_, c) in &best {
        for ka in -1..=1 {
            let theta = c.theta + f64::from(ka) * fine_angle;
            rotate(points, theta, &mut rotated);
            cells_of(fine, &rotated, c.x, c.y, &mut cells);
            for ky in -2..=2 {
                for kx in -2..=2 {
                    let score = score_shifted(fine, &cells, kx, ky);
                    if score > top.0 {
                        let (x, y) = (
                            c.x + f64::from(kx) * fine.resolution,
                            c.y + f64::from(ky) * fine.resolution,
                        );
                        top = (score, Pose2::new(x, y, theta));
                    }
                }
            }
        }
    }

    let (score, pose) = refine(fine, points, top.1, fine.resolution, fine_angle);
    let response = score / n;
    let covariance = spread(fine, points, pose, response, fine_angle);
    Some(Match {
        pose: Pose2::new(pose.x, pose.y, wrap_angle(pose.theta)),
        response,
        covariance,
    })
}

/// Hill-climbs on the interpolated field from `start`, halving the steps each level.
fn refine(field: &Field, points: &[Point2], start: Pose2, step: f64, angle: f64) -> (f64, Pose2) {
    let mut rotated = Vec::with_capacity(points.len());
    let mut score_of = |p: Pose2| {
        rotate(points, p.theta, &mut rotated);
        rotated
            .iter()
            .map(|q| field.bilinear(p.x + q.x, p.y + q.y))
            .sum::<f64>()
    };
    let (mut pose, mut score) = (start, score_of(start));
    let (mut step, mut angle) = (step / 2.0, angle / 2.0);
    for _ in 0..REFINE_LEVELS {
        let mut moved = true;
        let mut rounds = 0;
        while moved && rounds < 10 {
            moved = false;
            rounds += 1;
            for d in [
                (step, 0.0, 0.0),
                (-step, 0.0, 0.0),
                (0.0, step, 0.0),
                (0.0, -step, 0.0),
                (0.0, 0.0, angle),
                (0.0, 0.0, -angle),
            ] {
                let p = Pose2::new(pose.x + d.0, pose.y + d.1, pose.theta + d.2);
                let s = score_of(p);
                if s > score {
                    (pose, score, moved) = (p, s, true);
                }
            }
        }
        step /= 2.0;
        angle /= 2.0;
    }
    (score, pose)
}

/// The covariance of the pose from how the response falls off round `best`: positions
/// at the best heading and headings at the best position, each weighted by
/// exp(-(response drop) / SPREAD_SCALE) (after Olson 2009 section III-C).
fn spread(
    field: &Field,
    points: &[Point2],
    best: Pose2,
    response: f64,
    angle_step: f64,
) -> Matrix3<f64> {
    let n = points.len() as f64;
    let r = field.resolution;
    let mut rotated = Vec::with_capacity(points.len());
    rotate(points, best.theta, &mut rotated);
    let (mut w_sum, mut xx, mut xy, mut yy) = (0.0, 0.0, 0.0, 0.0);
    for ky in -SPREAD_CELLS..=SPREAD_CELLS {
        for kx in -SPREAD_CELLS..=SPREAD_CELLS {
            let (dx, dy) = (f64::from(kx) * r, f64::from(ky) * r);
            let s: f64 = (rotated.iter())
                .map(|q| field.bilinear(best.x + dx + q.x, best.y + dy + q.y))
                .sum();
            let w = (-(response - s / n).max(0.0) / SPREAD_SCALE).exp();
            w_sum += w;
            xx += w * dx * dx;
            xy += w * dx * dy;
            yy += w * dy * dy;
        }
    }
    let (mut wa, mut aa) = (0.0, 0.0);
    for ka in -SPREAD_CELLS..=SPREAD_CELLS {
        let da = f64::from(ka) * angle_step;
        rotate(points, best.theta + da, &mut rotated);
        let s: f64 = (rotated.iter())
            .map(|q| field.bilinear(best.x + q.x, best.y + q.y))
            .sum();
        let w = (-(response - s / n).max(0.0) / SPREAD_SCALE).exp();
        wa += w;
        aa += w * da * da;
    }
    let floor_xy = (FLOOR_CELLS * r).powi(2);
    let floor_a = (angle_step / 2.0).powi(2);
    Matrix3::new(
        xx / w_sum + floor_xy,
        xy / w_sum,
        0.0,
        xy / w_sum,
        yy / w_sum + floor_xy,
        0.0,
        0.0,
        0.0,
        aa / wa + floor_a,
    )
}

/// `points` turned by `theta`, into `out`.
fn rotate(points: &[Point2], theta: f64, out: &mut Vec<Point2>) {
    let (s, c) = theta.sin_cos();
    out.clear();
    out.extend(
        points
            .iter()
            .map(|p| Point2::new(c * p.x - s * p.y, s * p.x + c * p.y)),
    );
}

/// The cells (column, row) of the rotated points placed at (x, y); shifting them by whole
/// cells is the same as shifting the points by whole cells' widths.
fn cells_of(field: &Field, rotated: &[Point2], x: f64, y: f64, out: &mut Vec<(i32, i32)>) {
    out.clear();
    out.extend(rotated.iter().map(|q| {
        (
            ((x + q.x - field.origin.x) / field.resolution).floor() as i32,
            ((y + q.y - field.origin.y) / field.resolution).floor() as i32,
        )
    }));
}

/// The sum of the field's cells under `cells` shifted by (kx, ky); 0 off the grid.
#[inline]
fn score_shifted(field: &Field, cells: &[(i32, i32)], kx: i32, ky: i32) -> f64 {
    let (w, h) = (field.width as u32, field.height as u32);
    let mut sum = 0.0f32;
    for &(cx, cy) in cells {
        let (x, y) = ((cx + kx) as u32, (cy + ky) as u32);
        if x < w && y < h {
            sum += field.values[(y * w + x) as usize];
        }
    }
    f64::from(sum)
}

/// Keeps the `CANDIDATES` best (score, pose) pairs.
fn keep_best(best: &mut Vec<(f64, Pose2)>, score: f64, pose: Pose2) {
    if best.len() == CANDIDATES && score <= best[CANDIDATES - 1].0 {
        return;
    }
    let at = best.partition_point(|(s, _)| *s >= score);
    best.insert(at, (score, pose));
    best.truncate(CANDIDATES);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points along the walls of a `w` x `h` room centred on the origin, every 2 cm.
    fn room(w: f64, h: f64) -> Vec<Point2> {
        let mut out = Vec::new();
        let n = 100;
        for k in 0..=n {
            let t = k as f64 / n as f64;
            out.push(Point2::new(-w / 2.0 + t * w, -h / 2.0));
            out.push(Point2::new(-w / 2.0 + t * w, h / 2.0));
            out.push(Point2::new(-w / 2.0, -h / 2.0 + t * h));
            out.push(Point2::new(w / 2.0, -h / 2.0 + t * h));
        }
        out
    }

    /// The world points seen from `pose`, in the robot frame.
    fn seen_from(world: &[Point2], pose: Pose2) -> Vec<Point2> {
        world
            .iter()
            .map(|p| pose.inverse_transform_point(*p))
            .collect()
    }

    #[test]
    fn a_room_is_found_from_an_offset_guess_and_pinned_tightly() {
        let walls = room(4.0, 3.0);
        let fine = Field::from_hits(&walls, 0.05, 0.05, 0.5).unwrap();
        let coarse = fine.coarser();
        let truth = Pose2::new(0.4, -0.3, 0.2);
        let points = seen_from(&walls, truth);
        let guess = Pose2::new(0.55, -0.2, 0.2 + 6f64.to_radians());
        let window = Window {
            half_width: 0.3,
            half_angle: 12f64.to_radians(),
        };
        let m = correlate(&fine, &coarse, &points, guess, window).unwrap();
        assert!(m.pose.position().distance(truth.position()) < 0.01, "{m:?}");
        assert!(wrap_angle(m.pose.theta - truth.theta).abs() < 0.5f64.to_radians());
        assert!(m.response > 0.8, "{}", m.response);
        assert!(m.position_std() < 0.03, "{}", m.position_std());
    }

    #[test]
    fn a_corridor_leaves_the_pose_along_it_uncertain() {
        // Two long parallel walls 1.2 m apart: nothing pins the pose along x.
        let walls: Vec<Point2> = (0..=400)
            .flat_map(|k| {
                let x = -10.0 + k as f64 * 0.05;
                [Point2::new(x, -0.6), Point2::new(x, 0.6)]
            })
            .collect();
        let fine = Field::from_hits(&walls, 0.05, 0.05, 0.5).unwrap();
        let coarse = fine.coarser();
        let near: Vec<Point2> = walls.iter().copied().filter(|p| p.x.abs() < 3.0).collect();
        let points = seen_from(&near, Pose2::default());
        let window = Window {
            half_width: 0.5,
            half_angle: 10f64.to_radians(),
        };
        let m = correlate(&fine, &coarse, &points, Pose2::default(), window).unwrap();
        let (sx, sy) = (m.covariance[(0, 0)].sqrt(), m.covariance[(1, 1)].sqrt());
        assert!(sx > 0.1, "along the corridor: {sx}");
        assert!(sy < 0.03, "across it: {sy}");
    }
}
