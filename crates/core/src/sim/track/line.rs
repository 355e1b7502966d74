//! The lane's geometry: a closed centreline, resampled evenly, with the lane's width
//! between the centres of its two lines.

use crate::geometry::{Point2, wrap_angle};

/// Spacing of the resampled centreline, metres.
pub const STEP: f64 = 0.02;

/// A closed lane: the yellow line runs `lane_width / 2` left of the centreline, the white
/// one as far right (seen driving forward along it).
#[derive(Clone, Debug, PartialEq)]
pub struct Track {
    /// The centreline, evenly spaced `STEP` apart; the last point joins the first.
    points: Vec<Point2>,
    /// Arc length at each point, metres.
    along: Vec<f64>,
    length: f64,
    /// Distance between the centres of the two lines, metres.
    pub lane_width: f64,
    /// Width of each painted line, metres.
    pub line_width: f64,
    /// Whether the white line is dashed (`dash` painted, `dash` gap).
    pub white_dashed: bool,
    pub dash: f64,
}

/// Where a point lies relative to the lane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrackPoint {
    /// Arc length along the centreline of the nearest point, metres, in [0, length).
    pub along: f64,
    /// Signed distance from the centreline, metres, positive to the left.
    pub offset: f64,
    /// Heading of the centreline there, radians.
    pub heading: f64,
}

impl Track {
    /// The lane along the closed polyline `corners`, resampled every `STEP` metres.
    /// None when it has under three points or no length.
    pub fn new(
        corners: &[Point2],
        lane_width: f64,
        line_width: f64,
        white_dashed: bool,
        dash: f64,
    ) -> Option<Self> {
        if corners.len() < 3 {
            return None;
        }
        let n = corners.len();
        let total: f64 = (0..n)
            .map(|i| corners[i].distance(corners[(i + 1) % n]))
            .sum();
        if !(total.is_finite() && total > STEP) {
            return None;
        }
        let count = (total / STEP).round().max(3.0) as usize;
        let step = total / count as f64;
        let mut points = Vec::with_capacity(count);
        let (mut i, mut start) = (0, 0.0);
        for k in 0..count {
            let s = k as f64 * step;
            while i + 1 < n && start + corners[i].distance(corners[i + 1]) < s {
                start += corners[i].distance(corners[i + 1]);
                i += 1;
            }
            let (a, b) = (corners[i], corners[(i + 1) % n]);
            let len = a.distance(b).max(1e-12);
            let f = ((s - start) / len).clamp(0.0, 1.0);
            points.push(Point2::new(a.x + f * (b.x - a.x), a.y + f * (b.y - a.y)));
        }
        let along = (0..count).map(|k| k as f64 * step).collect();
        Some(Self {
            points,
            along,
            length: total,
            lane_width,
            line_width,
            white_dashed,
            dash,
        })
    }

    /// The resampled centreline.
    pub fn points(&self) -> &[Point2] {
        &self.points
    }

    /// The lane's length round, metres.
    pub fn length(&self) -> f64 {
        self.length
    }

    /// The point and heading `s` metres along the centreline (any `s`, taken round).
    pub fn at(&self, s: f64) -> (Point2, f64) {
        let n = self.points.len();
        let s = s.rem_euclid(self.length);
        let step = self.length / n as f64;
        let i = ((s / step) as usize).min(n - 1);
        let (a, b) = (self.points[i], self.points[(i + 1) % n]);
        let f = (s - self.along[i]) / step;
        let p = Point2::new(a.x + f * (b.x - a.x), a.y + f * (b.y - a.y));
        (p, (b.y - a.y).atan2(b.x - a.x))
    }

    /// Where `p` lies: the nearest point of the centreline, its arc length and heading,
    /// and the signed distance across.
    pub fn project(&self, p: Point2) -> TrackPoint {
        let n = self.points.len();
        let mut best = (f64::INFINITY, 0, 0.0);
        for i in 0..n {
            let (a, b) = (self.points[i], self.points[(i + 1) % n]);
            let (dx, dy) = (b.x - a.x, b.y - a.y);
            let len2 = (dx * dx + dy * dy).max(1e-18);
            let f = (((p.x - a.x) * dx + (p.y - a.y) * dy) / len2).clamp(0.0, 1.0);
            let (qx, qy) = (a.x + f * dx, a.y + f * dy);
            let d2 = (p.x - qx).powi(2) + (p.y - qy).powi(2);
            if d2 < best.0 {
                best = (d2, i, f);
            }
        }
        let (d2, i, f) = best;
        let (a, b) = (self.points[i], self.points[(i + 1) % n]);
        let heading = (b.y - a.y).atan2(b.x - a.x);
        // Left of the direction of travel is positive: the cross product's sign.
        let cross = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
        let step = self.length / n as f64;
        TrackPoint {
            along: (self.along[i] + f * step).rem_euclid(self.length),
            offset: d2.sqrt().copysign(cross),
            heading,
        }
    }

    /// The line `offset` metres left of the centreline (negative: right), closed.
    pub fn offset_line(&self, offset: f64) -> Vec<Point2> {
        let n = self.points.len();
        (0..n)
            .map(|i| {
                let (prev, next) = (self.points[(i + n - 1) % n], self.points[(i + 1) % n]);
                let heading = (next.y - prev.y).atan2(next.x - prev.x);
                let (s, c) = heading.sin_cos();
                let p = self.points[i];
                Point2::new(p.x - s * offset, p.y + c * offset)
            })
            .collect()
    }

    /// The heading error of a robot heading `theta` at `p`: its heading less the lane's.
    pub fn heading_error(&self, p: Point2, theta: f64) -> f64 {
        wrap_angle(theta - self.project(p).heading)
    }

    /// The smallest radius of curvature round the lane, metres, from the turn between
    /// points `window` apart (Menger curvature of three points, 4 area / product of sides).
    pub fn min_radius(&self, window: usize) -> f64 {
        let n = self.points.len();
        let w = window.clamp(1, n / 3);
        (0..n)
            .map(|i| {
                let (a, b, c) = (
                    self.points[(i + n - w) % n],
                    self.points[i],
                    self.points[(i + w) % n],
                );
                let area2 = ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)).abs();
                let sides = a.distance(b) * b.distance(c) * c.distance(a);
                if area2 < 1e-12 {
                    f64::INFINITY
                } else {
                    sides / (2.0 * area2)
                }
            })
            .fold(f64::INFINITY, f64::min)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Track {
        let c = [(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)].map(|(x, y)| Point2::new(x, y));
        Track::new(&c, 0.4, 0.02, false, 0.1).unwrap()
    }

    #[test]
    fn a_point_left_of_the_lane_has_a_positive_offset_and_its_arc_length() {
        let t = square();
        assert!((t.length() - 8.0).abs() < 1e-9);
        let p = t.project(Point2::new(1.0, 0.1));
        assert!(
            (p.along - 1.0).abs() < 1e-9 && (p.offset - 0.1).abs() < 1e-9,
            "{p:?}"
        );
        let p = t.project(Point2::new(2.15, 1.0));
        assert!(
            (p.along - 3.0).abs() < 1e-9 && (p.offset + 0.15).abs() < 1e-9,
            "{p:?}"
        );
        assert!((p.heading - std::f64::consts::FRAC_PI_2).abs() < 1e-9);
    }

    #[test]
    fn at_goes_round() {
        let t = square();
        let (p, h) = t.at(9.0);
        assert!((p.x - 1.0).abs() < 1e-9 && p.y.abs() < 1e-9 && h.abs() < 1e-9);
    }

    #[test]
    fn a_circle_has_its_radius() {
        let c: Vec<Point2> = (0..400)
            .map(|i| {
                let a = i as f64 * std::f64::consts::TAU / 400.0;
                Point2::new(1.5 * a.cos(), 1.5 * a.sin())
            })
            .collect();
        let t = Track::new(&c, 0.4, 0.02, true, 0.1).unwrap();
        assert!(
            (t.min_radius(10) - 1.5).abs() < 0.01,
            "{}",
            t.min_radius(10)
        );
        let left = t.offset_line(0.2);
        assert!((left[0].x.hypot(left[0].y) - 1.3).abs() < 0.01);
    }
}
