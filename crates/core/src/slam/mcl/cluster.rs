//! The pose the particle cloud stands for: particles binned as KLD-sampling bins them,
//! neighbouring bins joined into clusters, and the heaviest cluster's weighted mean and
//! covariance taken as the estimate (AMCL's cluster statistics). A cloud split between
//! two places, as in a symmetric map, keeps two clusters and is not converged.

use crate::geometry::{Pose2, wrap_angle};
use nalgebra::{Matrix3, Vector3};
use std::collections::HashMap;

/// A histogram bin: x, y and heading indices.
pub type Bin = (i32, i32, i32);

/// The bin of `pose` for bins of `size` metres and `angle` radians.
pub fn bin_of(pose: Pose2, size: f64, angle: f64) -> Bin {
    (
        (pose.x / size).floor() as i32,
        (pose.y / size).floor() as i32,
        (wrap_angle(pose.theta).rem_euclid(std::f64::consts::TAU) / angle).floor() as i32,
    )
}

/// The estimate from a weighted cloud.
#[derive(Clone, Debug, PartialEq)]
pub struct CloudEstimate {
    pub pose: Pose2,
    pub covariance: Matrix3<f64>,
    /// The share of the weight in the cluster the pose comes from.
    pub weight: f64,
    /// Clusters holding at least 1 % of the weight.
    pub clusters: usize,
    /// Those clusters' weighted mean poses and weights, heaviest first: the hypotheses.
    pub hypotheses: Vec<(Pose2, f64)>,
}

/// See the module comment. `weights` are normalised; `size` and `angle` are the bins'.
pub fn estimate(poses: &[Pose2], weights: &[f64], size: f64, angle: f64) -> CloudEstimate {
    let turns = (std::f64::consts::TAU / angle).ceil() as i32;
    let bins: Vec<Bin> = poses.iter().map(|&p| bin_of(p, size, angle)).collect();
    let mut bin_weight: HashMap<Bin, f64> = HashMap::new();
    for (b, w) in bins.iter().zip(weights) {
        *bin_weight.entry(*b).or_default() += w;
    }
    // Flood fill over occupied neighbouring bins (heading wraps round).
    let mut cluster_of: HashMap<Bin, usize> = HashMap::with_capacity(bin_weight.len());
    let mut cluster_weight: Vec<f64> = Vec::new();
    let mut keys: Vec<Bin> = bin_weight.keys().copied().collect();
    keys.sort_unstable();
    for start in keys {
        if cluster_of.contains_key(&start) {
            continue;
        }
        let id = cluster_weight.len();
        cluster_weight.push(0.0);
        let mut stack = vec![start];
        cluster_of.insert(start, id);
        while let Some((x, y, t)) = stack.pop() {
            cluster_weight[id] += bin_weight[&(x, y, t)];
            for dx in -1..=1 {
                for dy in -1..=1 {
                    for dt in -1..=1 {
                        let n = (x + dx, y + dy, (t + dt).rem_euclid(turns));
                        if bin_weight.contains_key(&n) && !cluster_of.contains_key(&n) {
                            cluster_of.insert(n, id);
                            stack.push(n);
                        }
                    }
                }
            }
        }
    }
    let best = (0..cluster_weight.len())
        .max_by(|&a, &b| cluster_weight[a].total_cmp(&cluster_weight[b]))
        .unwrap_or(0);
    let total = cluster_weight.get(best).copied().unwrap_or(0.0);
    let members: Vec<(Pose2, f64)> = (poses.iter().zip(weights).zip(&bins))
        .filter(|(_, b)| cluster_of.get(b) == Some(&best))
        .map(|((p, w), _)| (*p, *w))
        .collect();
    let (pose, covariance) = weighted_mean_and_covariance(&members);
    CloudEstimate {
        pose,
        covariance,
        weight: total,
        clusters: cluster_weight.iter().filter(|&&w| w >= HYPOTHESIS).count(),
        hypotheses: hypotheses(poses, weights, &bins, &cluster_of, &cluster_weight),
    }
}

/// A cluster counts as a hypothesis from this share of the weight.
const HYPOTHESIS: f64 = 0.01;

/// Each cluster of at least `HYPOTHESIS` of the weight: its weighted mean pose (heading
/// as a circular mean) and its weight, heaviest first.
fn hypotheses(
    poses: &[Pose2],
    weights: &[f64],
    bins: &[Bin],
    cluster_of: &HashMap<Bin, usize>,
    cluster_weight: &[f64],
) -> Vec<(Pose2, f64)> {
    // Sums of w·x, w·y, w·cos θ, w·sin θ per cluster.
    let mut sums = vec![[0.0f64; 4]; cluster_weight.len()];
    for ((p, w), b) in poses.iter().zip(weights).zip(bins) {
        let s = &mut sums[cluster_of[b]];
        s[0] += w * p.x;
        s[1] += w * p.y;
        s[2] += w * p.theta.cos();
        s[3] += w * p.theta.sin();
    }
    let mut out: Vec<(Pose2, f64)> = (sums.iter().zip(cluster_weight))
        .filter(|(_, w)| **w >= HYPOTHESIS)
        .map(|(s, &w)| (Pose2::new(s[0] / w, s[1] / w, s[3].atan2(s[2])), w))
        .collect();
    out.sort_by(|a, b| b.1.total_cmp(&a.1));
    out
}

/// The weighted mean (the heading as a circular mean) and covariance of weighted poses.
pub fn weighted_mean_and_covariance(members: &[(Pose2, f64)]) -> (Pose2, Matrix3<f64>) {
    let total: f64 = members.iter().map(|(_, w)| w).sum();
    if members.is_empty() || total <= 0.0 {
        return (Pose2::default(), Matrix3::identity());
    }
    let (mut x, mut y, mut c, mut s) = (0.0, 0.0, 0.0, 0.0);
    for (p, w) in members {
        x += w * p.x;
        y += w * p.y;
        c += w * p.theta.cos();
        s += w * p.theta.sin();
    }
    let mean = Pose2::new(x / total, y / total, s.atan2(c));
    let mut cov = Matrix3::zeros();
    for (p, w) in members {
        let e = Vector3::new(p.x - mean.x, p.y - mean.y, wrap_angle(p.theta - mean.theta));
        cov += (w / total) * e * e.transpose();
    }
    (mean, cov)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_separate_groups_make_two_clusters_and_the_heavier_wins() {
        let mut poses = vec![];
        let mut weights = vec![];
        for i in 0..10 {
            poses.push(Pose2::new(1.0 + 0.01 * i as f64, 1.0, 0.1));
            weights.push(0.07);
            poses.push(Pose2::new(5.0, 5.0 + 0.01 * i as f64, 3.0));
            weights.push(0.03);
        }
        let e = estimate(&poses, &weights, 0.5, 10f64.to_radians());
        assert_eq!(e.clusters, 2);
        assert!((e.weight - 0.7).abs() < 1e-9);
        // The hypotheses, heaviest first, at their clusters' means.
        assert_eq!(e.hypotheses.len(), 2);
        let (second, w) = e.hypotheses[1];
        assert!(
            (w - 0.3).abs() < 1e-9 && (second.x - 5.0).abs() < 1e-9,
            "{second:?}"
        );
        assert!((second.y - 5.045).abs() < 1e-9 && (second.theta - 3.0).abs() < 1e-9);
        assert!((e.pose.x - 1.045).abs() < 1e-9 && (e.pose.y - 1.0).abs() < 1e-9);
        assert!((e.pose.theta - 0.1).abs() < 1e-9);
    }

    #[test]
    fn headings_either_side_of_pi_average_to_pi_and_join_one_cluster() {
        let poses = [Pose2::new(0.1, 0.1, 3.1), Pose2::new(0.1, 0.1, -3.1)];
        let e = estimate(&poses, &[0.5, 0.5], 0.5, 10f64.to_radians());
        assert_eq!(e.clusters, 1);
        assert!((e.pose.theta.abs() - std::f64::consts::PI).abs() < 1e-9);
        // The spread in heading is π - 3.1 either side.
        let sd = e.covariance[(2, 2)].sqrt();
        assert!((sd - (std::f64::consts::PI - 3.1)).abs() < 1e-9, "{sd}");
    }
}
