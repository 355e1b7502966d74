//! What lets the filter find a robot it lost: augmented MCL's short- and long-term
//! averages of the scans' fit, and the random particles it adds while they disagree
//! (Probabilistic Robotics table 8.3).

use super::known_map::KnownMap;
use crate::geometry::Pose2;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// A pose on a known free cell, anywhere in it, heading at random.
pub(super) fn random_free_pose(map: &KnownMap, rng: &mut ChaCha8Rng) -> Pose2 {
    let free = map.free_cells();
    let cell = free[rng.random_range(0..free.len())] as usize;
    let c = map.center(cell);
    let h = map.resolution / 2.0;
    Pose2::new(
        c.x + rng.random_range(-h..h),
        c.y + rng.random_range(-h..h),
        rng.random_range(-std::f64::consts::PI..std::f64::consts::PI),
    )
}

/// An exponential average w += α (x - w) from w = 0 (Probabilistic Robotics table 8.3,
/// lines 10-11), read corrected for its start: divided by 1 - (1 - α)^k after k samples,
/// so that until about 1/α samples it is the mean of those seen, not the first one.
/// Anchored at the first sample, the slow average would remember the poor fit of a
/// global localisation's first scans for a thousand updates, and a kidnapping soon after
/// would go unnoticed.
#[derive(Clone, Copy, Debug)]
pub(super) struct Average {
    alpha: f64,
    raw: f64,
    /// (1 - α)^k.
    decay: f64,
}

impl Average {
    pub(super) fn new(alpha: f64) -> Self {
        Self {
            alpha,
            raw: 0.0,
            decay: 1.0,
        }
    }

    pub(super) fn add(&mut self, x: f64) {
        self.raw += self.alpha * (x - self.raw);
        self.decay *= 1.0 - self.alpha;
    }

    pub(super) fn value(&self) -> f64 {
        let weight = 1.0 - self.decay;
        if weight > 0.0 { self.raw / weight } else { 0.0 }
    }
}
