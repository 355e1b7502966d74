//! From line segments to one arm: segments joined into clusters when they come within a
//! few pixels of each other (seed 000 §3.2.2 clusters with DBSCAN, eps 20), and the
//! principal axis of the biggest cluster's endpoints, weighted by segment length (§3.2.2's
//! PCA). Plain Rust: a frame holds tens of segments.

/// A segment's endpoints, pixels.
pub type Segment = [f64; 4];

/// The arm's axis as seen: two endpoints, the spread across it and the cluster's share of
/// all segment length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Axis {
    pub ends: [(f64, f64); 2],
    /// Standard deviation of the points across the axis, pixels.
    pub spread: f64,
    pub share: f64,
}

fn length(s: &Segment) -> f64 {
    (s[2] - s[0]).hypot(s[3] - s[1])
}

/// Distance from point p to segment s (Eberly, Geometric Tools, 6.1).
fn point_to_segment(p: (f64, f64), s: &Segment) -> f64 {
    let (dx, dy) = (s[2] - s[0], s[3] - s[1]);
    let l2 = dx * dx + dy * dy;
    let t = if l2 > 0.0 {
        (((p.0 - s[0]) * dx + (p.1 - s[1]) * dy) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p.0 - s[0] - t * dx).hypot(p.1 - s[1] - t * dy)
}

/// Least distance between two segments that do not cross: an endpoint of one to the other.
fn gap(a: &Segment, b: &Segment) -> f64 {
    [
        point_to_segment((a[0], a[1]), b),
        point_to_segment((a[2], a[3]), b),
        point_to_segment((b[0], b[1]), a),
        point_to_segment((b[2], b[3]), a),
    ]
    .into_iter()
    .fold(f64::INFINITY, f64::min)
}

/// Whether two segments belong to one arm: within `eps` of each other, or in line (within
/// 10 degrees, each one's middle within eps / 2 of the other's line) and within 4 eps, so
/// the stripes of an arm, edges broken by the light stripes between, stay together.
fn linked(a: &Segment, b: &Segment, eps: f64) -> bool {
    let g = gap(a, b);
    if g <= eps {
        return true;
    }
    if g > 4.0 * eps {
        return false;
    }
    let angle = |s: &Segment| (s[3] - s[1]).atan2(s[2] - s[0]);
    let turn = (angle(a) - angle(b)).rem_euclid(std::f64::consts::PI);
    let turn = turn.min(std::f64::consts::PI - turn);
    let off_line = |s: &Segment, t: &Segment| {
        // Distance from s's middle to t's line (Eberly 6.1 without the clamp).
        let (mx, my) = ((s[0] + s[2]) / 2.0, (s[1] + s[3]) / 2.0);
        let (dx, dy) = (t[2] - t[0], t[3] - t[1]);
        ((mx - t[0]) * dy - (my - t[1]) * dx).abs() / dx.hypot(dy).max(1e-9)
    };
    turn < 10f64.to_radians() && off_line(a, b) <= eps / 2.0 && off_line(b, a) <= eps / 2.0
}

fn root(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

/// Clusters of segments linked by gaps of at most `eps` pixels (single linkage, the
/// DBSCAN of seed 000 §3.2.2 with one sample per core), as lists of indices.
pub fn clusters(segments: &[Segment], eps: f64) -> Vec<Vec<usize>> {
    let mut parent: Vec<usize> = (0..segments.len()).collect();
    for i in 0..segments.len() {
        for j in i + 1..segments.len() {
            if linked(&segments[i], &segments[j], eps) {
                let (a, b) = (root(&mut parent, i), root(&mut parent, j));
                parent[a] = b;
            }
        }
    }
    let mut groups: Vec<Vec<usize>> = Vec::new();
    let mut slot = vec![usize::MAX; segments.len()];
    for i in 0..segments.len() {
        let r = root(&mut parent, i);
        if slot[r] == usize::MAX {
            slot[r] = groups.len();
            groups.push(Vec::new());
        }
        groups[slot[r]].push(i);
    }
    groups
}

/// The axis of the cluster with the most segment length, none without segments.
pub fn arm_axis(segments: &[Segment], eps: f64) -> Option<Axis> {
    let total: f64 = segments.iter().map(length).sum();
    let groups = clusters(segments, eps);
    let best = groups.iter().max_by(|a, b| {
        let la: f64 = a.iter().map(|&i| length(&segments[i])).sum();
        let lb: f64 = b.iter().map(|&i| length(&segments[i])).sum();
        la.total_cmp(&lb)
    })?;
    // Endpoints weighted by their segment's length.
    let points: Vec<((f64, f64), f64)> = best
        .iter()
        .flat_map(|&i| {
            let s = &segments[i];
            let w = length(s);
            [((s[0], s[1]), w), ((s[2], s[3]), w)]
        })
        .collect();
    let weight: f64 = points.iter().map(|p| p.1).sum();
    if weight <= 0.0 {
        return None;
    }
    let mean = points.iter().fold((0.0, 0.0), |m, (p, w)| {
        (m.0 + p.0 * w / weight, m.1 + p.1 * w / weight)
    });
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for ((x, y), w) in &points {
        let (dx, dy) = (x - mean.0, y - mean.1);
        sxx += w * dx * dx / weight;
        sxy += w * dx * dy / weight;
        syy += w * dy * dy / weight;
    }
    // Principal direction of the 2x2 covariance: theta = atan2(2 sxy, sxx - syy) / 2, and
    // its eigenvalues (Jolliffe, Principal Component Analysis, 1.1).
    let theta = 0.5 * (2.0 * sxy).atan2(sxx - syy);
    let dir = (theta.cos(), theta.sin());
    let half = ((sxx - syy) / 2.0).hypot(sxy);
    let minor = ((sxx + syy) / 2.0 - half).max(0.0);
    let along = |p: &(f64, f64)| (p.0 - mean.0) * dir.0 + (p.1 - mean.1) * dir.1;
    let lo = points
        .iter()
        .map(|p| along(&p.0))
        .fold(f64::INFINITY, f64::min);
    let hi = points
        .iter()
        .map(|p| along(&p.0))
        .fold(f64::NEG_INFINITY, f64::max);
    let at = |t: f64| (mean.0 + t * dir.0, mean.1 + t * dir.1);
    Some(Axis {
        ends: [at(lo), at(hi)],
        spread: minor.sqrt(),
        share: best.iter().map(|&i| length(&segments[i])).sum::<f64>() / total,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_edges_of_a_tilted_bar_give_its_axis_and_stray_segments_are_left_out() {
        // The top and bottom edges of a bar at 30 degrees, 10 px apart, in two pieces each,
        // and a stray segment far away.
        let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        let edge = |t0: f64, t1: f64, off: f64| -> Segment {
            [
                100.0 + t0 * c - off * s,
                100.0 + t0 * s + off * c,
                100.0 + t1 * c - off * s,
                100.0 + t1 * s + off * c,
            ]
        };
        let segments = [
            edge(0.0, 40.0, -5.0),
            edge(55.0, 100.0, -5.0),
            edge(0.0, 45.0, 5.0),
            edge(60.0, 100.0, 5.0),
            [400.0, 400.0, 430.0, 400.0],
        ];
        let axis = arm_axis(&segments, 20.0).unwrap();
        let [a, b] = axis.ends;
        let angle = (b.1 - a.1).atan2(b.0 - a.0).to_degrees().rem_euclid(180.0);
        assert!((angle - 30.0).abs() < 0.5, "{angle}");
        assert!((axis.spread - 5.0).abs() < 0.5, "{}", axis.spread);
        assert!((axis.share - 170.0 / 200.0).abs() < 1e-9, "{}", axis.share);
        assert_eq!(clusters(&segments, 20.0).len(), 2);
    }
}
