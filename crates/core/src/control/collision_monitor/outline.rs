//! A zone's outline as a closed polygon: whether a point lies inside, its area, and what
//! makes an outline unusable (too few corners, a fold, edges that cross).

use crate::geometry::Point2;
use crate::sim::shapes::segment_distance2;

/// Edges shorter than this are a repeated corner, metres.
pub const SHORTEST_EDGE: f64 = 0.001;
/// Outlines enclosing less than this are degenerate, m² (a square centimetre).
pub const SMALLEST_AREA: f64 = 1e-4;

/// True when `p` lies inside the closed polygon `corners` (even-odd rule: a ray from `p`
/// along +x crosses the outline an odd number of times; O'Rourke, Computational Geometry
/// in C, 2nd ed., section 7.4). A point that is not finite is outside.
pub fn contains(corners: &[Point2], p: Point2) -> bool {
    let mut inside = false;
    let mut previous = match corners.last() {
        Some(&c) => c,
        None => return false,
    };
    for &corner in corners {
        let (a, b) = (previous, corner);
        // The edge straddles the ray's line (half-open, so a shared corner counts once).
        if (a.y > p.y) != (b.y > p.y) {
            let x_at = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
            if p.x < x_at {
                inside = !inside;
            }
        }
        previous = corner;
    }
    inside
}

/// The area enclosed, positive when the corners run counter-clockwise (the shoelace
/// formula; O'Rourke section 1.3).
pub fn signed_area(corners: &[Point2]) -> f64 {
    let n = corners.len();
    (0..n)
        .map(|i| {
            let (a, b) = (corners[i], corners[(i + 1) % n]);
            a.x * b.y - b.x * a.y
        })
        .sum::<f64>()
        / 2.0
}

/// Why an outline of at least three finite corners is not a simple polygon, if it is not:
/// an edge too short, an edge folding back over the one before it, two edges that do not
/// share a corner crossing or touching, or too little area.
pub fn problem(corners: &[Point2]) -> Option<String> {
    let n = corners.len();
    let edge = |i: usize| (corners[i], corners[(i + 1) % n]);
    for i in 0..n {
        let (a, b) = edge(i);
        if a.distance(b) < SHORTEST_EDGE {
            return Some(format!(
                "corners {i} and {} are the same point: the outline needs distinct corners",
                (i + 1) % n
            ));
        }
    }
    for i in 0..n {
        let (a, b) = edge(i);
        let c = corners[(i + 2) % n];
        let (ab, bc) = ((b.x - a.x, b.y - a.y), (c.x - b.x, c.y - b.y));
        let cross = ab.0 * bc.1 - ab.1 * bc.0;
        let dot = ab.0 * bc.0 + ab.1 * bc.1;
        // Parallel and opposite: the next edge runs back along this one.
        if cross.abs() <= 1e-12 * (ab.0.hypot(ab.1) * bc.0.hypot(bc.1)) && dot < 0.0 {
            return Some(format!(
                "edge {} folds back over edge {i}: the outline must not cross itself",
                (i + 1) % n
            ));
        }
    }
    for i in 0..n {
        // Edges i and j share a corner when they are neighbours (j = i + 1, or the last
        // edge and the first).
        for j in i + 2..n {
            if i == 0 && j == n - 1 {
                continue;
            }
            let (a, b) = edge(i);
            let (c, d) = edge(j);
            let segment = crate::geometry::Segment::new(c, d);
            if segment_distance2(a, b, segment) < SHORTEST_EDGE * SHORTEST_EDGE {
                return Some(format!(
                    "edges {i} and {j} cross or touch: the outline must not cross itself"
                ));
            }
        }
    }
    let area = signed_area(corners).abs();
    (area < SMALLEST_AREA).then(|| {
        format!(
            "encloses {} m², under a square centimetre: the corners must enclose an area",
            crate::data::number::short(area)
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn outline(corners: &[(f64, f64)]) -> Vec<Point2> {
        corners.iter().map(|&(x, y)| Point2::new(x, y)).collect()
    }

    #[test]
    fn a_square_holds_its_middle_and_not_what_lies_beside_it() {
        let square = outline(&[(0.5, 0.25), (0.5, -0.25), (0.0, -0.25), (0.0, 0.25)]);
        assert!(contains(&square, Point2::new(0.25, 0.0)));
        assert!(contains(&square, Point2::new(0.49, 0.24)));
        assert!(!contains(&square, Point2::new(0.51, 0.0)));
        assert!(!contains(&square, Point2::new(-0.01, 0.0)));
        assert!(!contains(&square, Point2::new(0.25, 0.3)));
        assert!(!contains(&square, Point2::new(f64::NAN, 0.0)));
        // Clockwise here: the shoelace area is negative, its size 0.5 x 0.5.
        assert!((signed_area(&square) + 0.25).abs() < 1e-12);
    }

    #[test]
    fn a_concave_outline_leaves_its_notch_outside() {
        // A U opening forwards: the notch between its arms is not inside.
        let u = outline(&[
            (0.0, -0.3),
            (0.4, -0.3),
            (0.4, -0.1),
            (0.1, -0.1),
            (0.1, 0.1),
            (0.4, 0.1),
            (0.4, 0.3),
            (0.0, 0.3),
        ]);
        assert!(problem(&u).is_none());
        assert!(contains(&u, Point2::new(0.3, 0.2)));
        assert!(!contains(&u, Point2::new(0.3, 0.0)));
        assert!(contains(&u, Point2::new(0.05, 0.0)));
    }

    #[test]
    fn crossing_folded_repeated_and_flat_outlines_are_named() {
        let bow_tie = outline(&[(0.0, 0.0), (0.4, 0.4), (0.4, 0.0), (0.0, 0.4)]);
        assert!(problem(&bow_tie).unwrap().contains("edges 0 and 2 cross"));
        let folded = outline(&[(0.0, 0.0), (0.4, 0.0), (0.2, 0.0), (0.2, 0.3)]);
        assert!(problem(&folded).unwrap().contains("folds back"));
        let repeated = outline(&[(0.0, 0.0), (0.4, 0.0), (0.4, 0.0), (0.0, 0.3)]);
        assert!(problem(&repeated).unwrap().contains("same point"));
        let flat = outline(&[(0.0, 0.0), (0.4, 0.0), (0.2, 0.0002)]);
        assert!(problem(&flat).unwrap().contains("enclose an area"));
        let triangle = outline(&[(0.0, 0.0), (0.4, 0.0), (0.0, 0.3)]);
        assert_eq!(problem(&triangle), None);
    }
}
