//! `navdeck arm pick-test`: seed 000's pick sequence in the twin, many times over, with
//! the block's pose taken from the robot's own sensors: a block stands 20 to 45 cm ahead
//! of the camera; the robot looks at it, turns to face it and drives up to it on
//! odometry, looks again from there until the fused sightings place it finely, then the
//! arm goes above the block, descends and closes. The gripper tells whether the jaws
//! closed on something; a miss is retried with a fresh look, a bounded number of times.
//! A pick succeeds when the twin's truth has the block in the jaws after the lift. The
//! error is how far the estimated block centre was from the true one when the arm last
//! went for it.

mod sequence;

use crate::config::Config;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

pub use sequence::{ATTEMPTS, Setup, pick};

/// Distances from the camera's side of the robot, metres (seed 000 section 6.1.2's
/// 20-45 cm), and the bearing the block may stand at either side.
const BANDS: [(f64, f64); 5] = [
    (0.20, 0.25),
    (0.25, 0.30),
    (0.30, 0.35),
    (0.35, 0.40),
    (0.40, 0.45),
];
const BEARING: f64 = 0.3;

/// One pick's outcome.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Pick {
    pub distance: f64,
    /// How far the estimated block was from the true one when the arm last went for it;
    /// none when the camera never saw it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error_mm: Option<f64>,
    /// The twin's truth: the block in the jaws after the lift.
    pub success: bool,
    /// Reaches made (1 when the first closed on the block).
    pub attempts: usize,
    /// Reaches whose jaws the gripper reported closed on nothing.
    pub misses: usize,
    /// Twin time from the first look to the end of the pick, seconds.
    pub time_s: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub why: Option<String>,
    /// What the pick did, a line per look, reach and miss.
    pub log: Vec<String>,
}

/// Outcomes per distance band.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Band {
    pub from_m: f64,
    pub to_m: f64,
    pub picks: usize,
    pub successes: usize,
    pub success_rate: f64,
    /// Over the band's picks whose block was seen; none when none was.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mean_error_mm: Option<f64>,
    /// Reaches that closed on nothing, and picks that needed more than one reach.
    pub misses: usize,
    pub retried: usize,
    /// Over the band's picks; none without picks.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mean_time_s: Option<f64>,
}

/// `picks` picks from `seed`, with the twin of `config` (its `[arm]`, or the default arm).
pub fn run(config: &Config, picks: usize, seed: u64) -> (Vec<Pick>, Vec<Band>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let all: Vec<Pick> = (0..picks)
        .map(|k| {
            let (lo, hi) = BANDS[k % BANDS.len()];
            let setup = Setup {
                distance: rng.random_range(lo..hi),
                bearing: rng.random_range(-BEARING..BEARING),
                seed: seed.wrapping_mul(1000).wrapping_add(k as u64),
                nudge: None,
            };
            pick(config, &setup)
        })
        .collect();
    let bands = BANDS
        .iter()
        .map(|&(lo, hi)| {
            let these: Vec<&Pick> = all
                .iter()
                .filter(|p| (lo..hi).contains(&p.distance))
                .collect();
            let n = these.len();
            let ok = these.iter().filter(|p| p.success).count();
            Band {
                from_m: lo,
                to_m: hi,
                picks: n,
                successes: ok,
                success_rate: ok as f64 / n.max(1) as f64,
                mean_error_mm: mean(these.iter().filter_map(|p| p.error_mm)),
                misses: these.iter().map(|p| p.misses).sum(),
                retried: these.iter().filter(|p| p.attempts > 1).count(),
                mean_time_s: mean(these.iter().map(|p| p.time_s)),
            }
        })
        .collect();
    (all, bands)
}

/// The mean of `values`, none of none.
fn mean(values: impl Iterator<Item = f64>) -> Option<f64> {
    let (sum, n) = values.fold((0.0, 0usize), |(sum, n), v| (sum + v, n + 1));
    (n > 0).then(|| sum / n as f64)
}
