//! Small planar shapes the twin is built from: rotated rectangles and segment distances.

use crate::geometry::{Point2, Pose2, Segment};

/// Corners of a `w` x `h` rectangle centred on `pose`, counter-clockwise starting at the
/// (+x, -y) corner, so edge k runs along face k of the order +x, +y, -x, -y.
pub fn rect_corners(pose: Pose2, w: f64, h: f64) -> [Point2; 4] {
    let (hw, hh) = (w / 2.0, h / 2.0);
    [(hw, -hh), (hw, hh), (-hw, hh), (-hw, -hh)]
        .map(|(x, y)| pose.transform_point(Point2::new(x, y)))
}

/// The four edges of a rectangle, in face order +x, +y, -x, -y.
pub fn rect_edges(pose: Pose2, w: f64, h: f64) -> [Segment; 4] {
    let c = rect_corners(pose, w, h);
    [0, 1, 2, 3].map(|k| Segment::new(c[k], c[(k + 1) % 4]))
}

/// Centre and outward facing (radians) of each face of a rectangle, order +x, +y, -x, -y.
pub fn rect_faces(pose: Pose2, w: f64, h: f64) -> [(Point2, f64); 4] {
    let (hw, hh) = (w / 2.0, h / 2.0);
    let local = [(hw, 0.0), (0.0, hh), (-hw, 0.0), (0.0, -hh)];
    let mut out = [(Point2::default(), 0.0); 4];
    for (k, (x, y)) in local.into_iter().enumerate() {
        let facing = pose.theta + k as f64 * std::f64::consts::FRAC_PI_2;
        out[k] = (pose.transform_point(Point2::new(x, y)), facing);
    }
    out
}

/// True when `p` lies inside (or on) the rectangle.
pub fn rect_contains(pose: Pose2, w: f64, h: f64, p: Point2) -> bool {
    let l = pose.inverse_transform_point(p);
    l.x.abs() <= w / 2.0 && l.y.abs() <= h / 2.0
}

/// Twice the signed area of triangle a-b-c: positive when c lies left of a->b
/// (the orientation test of de Berg et al., Computational Geometry, 3rd ed., section 1.1).
fn orient(a: Point2, b: Point2, c: Point2) -> f64 {
    (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)
}

/// True when the closed segments p0-p1 and q0-q1 cross or touch (proper or improper).
pub fn segments_cross(p0: Point2, p1: Point2, q0: Point2, q1: Point2) -> bool {
    let (d1, d2) = (orient(q0, q1, p0), orient(q0, q1, p1));
    let (d3, d4) = (orient(p0, p1, q0), orient(p0, p1, q1));
    // Straddle test (Cormen et al., Introduction to Algorithms, 33.1); collinear overlaps
    // fall to the distance check.
    ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
}

/// Squared distance from `p` to the segment a-b: orthogonal projection clamped to the ends
/// (the same rule as `Segment::distance_to`, without the square root).
pub fn dist2_to_segment(p: Point2, a: Point2, b: Point2) -> f64 {
    let (ex, ey) = (b.x - a.x, b.y - a.y);
    let (wx, wy) = (p.x - a.x, p.y - a.y);
    let len2 = ex * ex + ey * ey;
    let t = if len2 > 0.0 {
        ((wx * ex + wy * ey) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (dx, dy) = (wx - t * ex, wy - t * ey);
    dx * dx + dy * dy
}

/// Squared shortest distance between the segments p0-p1 and `s`: zero when they cross, else
/// the smallest of the four endpoint-to-segment distances (the minimum lies at an endpoint).
pub fn segment_distance2(p0: Point2, p1: Point2, s: Segment) -> f64 {
    if segments_cross(p0, p1, s.a, s.b) {
        return 0.0;
    }
    dist2_to_segment(p0, s.a, s.b)
        .min(dist2_to_segment(p1, s.a, s.b))
        .min(dist2_to_segment(s.a, p0, p1))
        .min(dist2_to_segment(s.b, p0, p1))
}

/// Euclidean distance with a plain square root (libm's `hypot` guards against overflow
/// that metre-scale worlds never reach, and is several times slower).
pub fn dist(a: Point2, b: Point2) -> f64 {
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    (dx * dx + dy * dy).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rectangle_faces_point_outward() {
        let pose = Pose2::new(1.0, 2.0, std::f64::consts::FRAC_PI_2);
        let faces = rect_faces(pose, 0.4, 0.2);
        // Local +x face of a box turned 90 degrees lies at +y in the world, facing +y.
        assert!((faces[0].0.x - 1.0).abs() < 1e-12 && (faces[0].0.y - 2.2).abs() < 1e-12);
        assert!((faces[0].1 - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        assert!(rect_contains(pose, 0.4, 0.2, Point2::new(1.05, 2.15)));
        assert!(!rect_contains(pose, 0.4, 0.2, Point2::new(1.15, 2.0)));
    }

    #[test]
    fn squared_distances_of_points_and_segments() {
        let wall = Segment::new(Point2::new(0.0, -1.0), Point2::new(0.0, 1.0));
        assert_eq!(
            segment_distance2(Point2::new(-1.0, 0.0), Point2::new(1.0, 0.0), wall),
            0.0
        );
        let d = segment_distance2(Point2::new(0.5, -1.0), Point2::new(0.5, 1.0), wall);
        assert!((d - 0.25).abs() < 1e-12);
        let d = segment_distance2(Point2::new(-1.0, 0.0), Point2::new(-0.3, 0.0), wall);
        assert!((d - 0.09).abs() < 1e-12);
        let p = Point2::new(0.3, 2.0);
        let exact = wall.distance_to(p);
        assert!((dist2_to_segment(p, wall.a, wall.b) - exact * exact).abs() < 1e-12);
        assert!((dist(Point2::new(1.0, 1.0), Point2::new(4.0, 5.0)) - 5.0).abs() < 1e-12);
    }
}
