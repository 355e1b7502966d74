//! Planar geometry shared by every layer: poses, twists, angle wrapping and segments.
//! Frames follow REP-103: x forward, y left, angles counter-clockwise positive, radians.

use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Wraps an angle to (-pi, pi] (seed 001 section 6 wraps the heading error to [-pi, pi),
/// which differs only at +-pi).
pub fn wrap_angle(a: f64) -> f64 {
    let mut w = a.rem_euclid(2.0 * PI);
    if w > PI {
        w -= 2.0 * PI;
    }
    w
}

/// A 2D point in metres.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Point2 {
    pub x: f64,
    pub y: f64,
}

impl Point2 {
    pub const fn new(x: f64, y: f64) -> Self {
        Self { x, y }
    }

    pub fn distance(self, other: Point2) -> f64 {
        (self.x - other.x).hypot(self.y - other.y)
    }
}

/// A robot pose in a planar frame: position in metres, heading in radians.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Pose2 {
    pub x: f64,
    pub y: f64,
    pub theta: f64,
}

impl Pose2 {
    pub const fn new(x: f64, y: f64, theta: f64) -> Self {
        Self { x, y, theta }
    }

    pub fn position(self) -> Point2 {
        Point2::new(self.x, self.y)
    }

    /// Maps a point given in this pose's frame into the parent frame.
    pub fn transform_point(self, local: Point2) -> Point2 {
        let (s, c) = self.theta.sin_cos();
        Point2::new(
            self.x + c * local.x - s * local.y,
            self.y + s * local.x + c * local.y,
        )
    }

    /// Maps a point given in the parent frame into this pose's frame.
    pub fn inverse_transform_point(self, world: Point2) -> Point2 {
        let (s, c) = self.theta.sin_cos();
        let dx = world.x - self.x;
        let dy = world.y - self.y;
        Point2::new(c * dx + s * dy, -s * dx + c * dy)
    }

    /// This pose followed by `local`, a pose given in this pose's frame (the SE(2)
    /// product, Smith, Self and Cheeseman's "head-to-tail" composition ⊕).
    pub fn compose(self, local: Pose2) -> Pose2 {
        let p = self.transform_point(local.position());
        Pose2::new(p.x, p.y, wrap_angle(self.theta + local.theta))
    }

    /// The pose that composes with this one to the identity (Smith, Self and Cheeseman's
    /// inverse ⊖).
    pub fn inverse(self) -> Pose2 {
        let (s, c) = self.theta.sin_cos();
        Pose2::new(
            -c * self.x - s * self.y,
            s * self.x - c * self.y,
            wrap_angle(-self.theta),
        )
    }

    /// `other` seen from this pose: `self.compose(self.between(other)) == other`.
    pub fn between(self, other: Pose2) -> Pose2 {
        self.inverse().compose(other)
    }
}

/// A velocity command or measurement: linear (m/s, forward positive) and angular (rad/s, CCW positive).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Twist {
    pub linear: f64,
    pub angular: f64,
}

impl Twist {
    pub const ZERO: Twist = Twist {
        linear: 0.0,
        angular: 0.0,
    };

    pub const fn new(linear: f64, angular: f64) -> Self {
        Self { linear, angular }
    }

    pub fn is_zero(self) -> bool {
        self.linear == 0.0 && self.angular == 0.0
    }

    /// The twist halfway to `other`, axis by axis: over a step whose speed ramps linearly
    /// from one to the other, it gives the exact travel (trapezoidal rule).
    pub fn halfway(self, other: Twist) -> Twist {
        Twist::new(
            (self.linear + other.linear) / 2.0,
            (self.angular + other.angular) / 2.0,
        )
    }
}

/// A line segment between two points, the building block of walls and obstacle outlines.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Segment {
    pub a: Point2,
    pub b: Point2,
}

impl Segment {
    pub const fn new(a: Point2, b: Point2) -> Self {
        Self { a, b }
    }

    pub fn length(self) -> f64 {
        self.a.distance(self.b)
    }

    /// The point of this segment nearest `p` (orthogonal projection clamped to the ends).
    pub fn closest_point(self, p: Point2) -> Point2 {
        let (dx, dy) = (self.b.x - self.a.x, self.b.y - self.a.y);
        let len2 = dx * dx + dy * dy;
        let t = if len2 > 0.0 {
            (((p.x - self.a.x) * dx + (p.y - self.a.y) * dy) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        Point2::new(self.a.x + t * dx, self.a.y + t * dy)
    }

    /// Shortest distance from `p` to this segment.
    pub fn distance_to(self, p: Point2) -> f64 {
        p.distance(self.closest_point(p))
    }

    /// The squared shortest distance, for comparisons that need no square root.
    pub fn distance_squared_to(self, p: Point2) -> f64 {
        let c = self.closest_point(p);
        (p.x - c.x).powi(2) + (p.y - c.y).powi(2)
    }

    /// Distance along the ray `origin + t * (cos a, sin a)` to this segment, if the ray hits it.
    pub fn ray_hit(self, origin: Point2, dir: (f64, f64)) -> Option<f64> {
        let (ex, ey) = (self.b.x - self.a.x, self.b.y - self.a.y);
        let denom = dir.0 * ey - dir.1 * ex;
        if denom.abs() < 1e-12 {
            return None;
        }
        let (wx, wy) = (self.a.x - origin.x, self.a.y - origin.y);
        let t = (wx * ey - wy * ex) / denom;
        let u = (wx * dir.1 - wy * dir.0) / denom;
        (t >= 0.0 && (0.0..=1.0).contains(&u)).then_some(t)
    }

    /// True when the open segment p-q crosses this segment.
    pub fn intersects(self, p: Point2, q: Point2) -> bool {
        let dir = (q.x - p.x, q.y - p.y);
        match self.ray_hit(p, dir) {
            Some(t) => t < 1.0,
            None => false,
        }
    }
}

/// A root mean square built up one sample at a time (cross-track errors, say).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rms {
    sum_squares: f64,
    count: usize,
}

impl Rms {
    pub fn add(&mut self, value: f64) {
        self.sum_squares += value * value;
        self.count += 1;
    }

    /// sqrt(sum of squares / count); `None` before the first sample.
    pub fn value(&self) -> Option<f64> {
        (self.count > 0).then(|| (self.sum_squares / self.count as f64).sqrt())
    }
}

/// Parses `X,Y,THETA_DEG` (metres and degrees, as the command line and `:pose` take a
/// pose) into a pose with its heading in radians.
pub fn parse_pose_degrees(s: &str) -> Result<Pose2, String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    let [x, y, deg] = parts.as_slice() else {
        return Err(format!("`{s}` is not X,Y,THETA_DEG"));
    };
    let number = |v: &str| {
        v.parse::<f64>()
            .ok()
            .filter(|n| n.is_finite() && n.abs() <= 1.0e5)
            .ok_or_else(|| format!("`{v}` in `{s}` is not a number within 100000"))
    };
    Ok(Pose2::new(
        number(x)?,
        number(y)?,
        wrap_angle(number(deg)?.to_radians()),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rms_of_known_samples() {
        let mut rms = Rms::default();
        assert_eq!(rms.value(), None);
        for v in [3.0, -4.0] {
            rms.add(v);
        }
        assert!((rms.value().unwrap() - 12.5f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn wrap_angle_lands_in_half_open_interval() {
        assert!((wrap_angle(3.0 * PI) - PI).abs() < 1e-12);
        assert!((wrap_angle(-PI) - PI).abs() < 1e-12);
        assert!((wrap_angle(-0.5) + 0.5).abs() < 1e-12);
        assert!((wrap_angle(2.0 * PI + 0.25) - 0.25).abs() < 1e-12);
    }

    #[test]
    fn composing_with_the_inverse_and_between_round_trip() {
        let a = Pose2::new(1.0, -2.0, 0.7);
        let b = Pose2::new(-0.5, 3.0, -2.9);
        let id = a.compose(a.inverse());
        assert!(id.x.abs() < 1e-12 && id.y.abs() < 1e-12 && id.theta.abs() < 1e-12);
        let back = a.compose(a.between(b));
        assert!((back.x - b.x).abs() < 1e-12 && (back.y - b.y).abs() < 1e-12);
        assert!(wrap_angle(back.theta - b.theta).abs() < 1e-12);
        // A quarter turn then one metre ahead ends one metre to the left.
        let q = Pose2::new(0.0, 0.0, PI / 2.0).compose(Pose2::new(1.0, 0.0, 0.0));
        assert!(q.x.abs() < 1e-12 && (q.y - 1.0).abs() < 1e-12);
    }

    #[test]
    fn pose_transforms_round_trip() {
        let pose = Pose2::new(1.0, -2.0, 0.7);
        let local = Point2::new(0.3, 0.4);
        let world = pose.transform_point(local);
        let back = pose.inverse_transform_point(world);
        assert!((back.x - local.x).abs() < 1e-12 && (back.y - local.y).abs() < 1e-12);
    }

    #[test]
    fn ray_hits_wall_at_expected_range() {
        let wall = Segment::new(Point2::new(2.0, -1.0), Point2::new(2.0, 1.0));
        let hit = wall.ray_hit(Point2::new(0.0, 0.0), (1.0, 0.0)).unwrap();
        assert!((hit - 2.0).abs() < 1e-12);
        assert!(wall.ray_hit(Point2::new(0.0, 0.0), (-1.0, 0.0)).is_none());
        assert!((wall.distance_to(Point2::new(0.0, 3.0)) - 8.0_f64.sqrt()).abs() < 1e-12);
    }
}
