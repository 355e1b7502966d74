//! The particle filter itself; see the module comment in `mod.rs`.

use super::cluster::{self, CloudEstimate};
use super::config::LocalizationConfig;
use super::known_map::KnownMap;
use super::motion::{self, OdometryStep};
use super::resample;
use super::sensor::{Beams, Weigher};
use crate::data::LaserScan;
use crate::geometry::{Point2, Pose2, wrap_angle};
use nalgebra::Matrix3;
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use std::sync::Arc;

/// One hypothesis of where the robot is, with its normalised weight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Particle {
    pub pose: Pose2,
    pub weight: f64,
}

/// What the status panel shows of the filter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Status {
    /// Particles now (KLD-sampling sets the count at each resampling).
    pub particles: usize,
    /// The effective sample size 1 / Σ w² of the last scan's normalised weights, before
    /// resampling (Probabilistic Robotics 4.3.4; AMCL resamples on it): how many
    /// particles carry the belief. Equal to `particles` until a scan has weighed them.
    pub effective: f64,
    /// The share of the weight behind the estimate.
    pub cluster_weight: f64,
    pub clusters: usize,
    pub converged: bool,
    /// The chance each resampled particle was replaced by a random one, last time.
    pub random_share: f64,
    pub updates: u64,
}

/// See the module comment.
pub struct Mcl {
    config: LocalizationConfig,
    map: Arc<KnownMap>,
    /// Built at the first scan, which tells the sensor's maximum range.
    weigher: Option<(f64, Weigher)>,
    particles: Vec<Particle>,
    rng: ChaCha8Rng,
    /// Augmented MCL's short- and long-term averages of the scans' fit (table 8.3).
    w_slow: Average,
    w_fast: Average,
    random_share: f64,
    /// The odometry pose at the last update: particles stand for the robot there.
    odom_at_update: Option<Pose2>,
    /// The next scan updates the filter even without motion (after a new initial pose).
    force_update: bool,
    estimate: CloudEstimate,
    converged: bool,
    effective: f64,
    updates: u64,
}

impl Mcl {
    /// A filter on `map` with no particles yet: place them with `init_at` or `init_global`.
    /// `seed` seeds its random numbers, so the same seed gives the same run.
    pub fn new(map: Arc<KnownMap>, config: &LocalizationConfig, seed: u64) -> Self {
        Self {
            config: config.clone(),
            map,
            weigher: None,
            particles: Vec::new(),
            rng: ChaCha8Rng::seed_from_u64(seed),
            w_slow: Average::new(config.alpha_slow),
            w_fast: Average::new(config.alpha_fast),
            random_share: 0.0,
            odom_at_update: None,
            force_update: true,
            estimate: CloudEstimate {
                pose: Pose2::default(),
                covariance: Matrix3::identity(),
                weight: 0.0,
                clusters: 0,
            },
            converged: false,
            effective: 0.0,
            updates: 0,
        }
    }

    pub fn map(&self) -> &Arc<KnownMap> {
        &self.map
    }

    /// Particles spread around `pose` with standard deviations `std_xy` (m) and
    /// `std_theta` (rad), as RViz's "2D Pose Estimate" places them.
    pub fn init_at(&mut self, pose: Pose2, std_xy: f64, std_theta: f64) {
        let n = self.config.max_particles as usize;
        let w = 1.0 / n as f64;
        let normal = |rng: &mut ChaCha8Rng| -> f64 { StandardNormal.sample(rng) };
        self.particles = (0..n)
            .map(|_| {
                let p = Pose2::new(
                    pose.x + std_xy * normal(&mut self.rng),
                    pose.y + std_xy * normal(&mut self.rng),
                    wrap_angle(pose.theta + std_theta * normal(&mut self.rng)),
                );
                Particle { pose: p, weight: w }
            })
            .collect();
        self.restart();
    }

    /// Global localisation: particles spread evenly over the map's free space, headings
    /// at random.
    pub fn init_global(&mut self) {
        let n = self.config.max_particles as usize;
        let w = 1.0 / n as f64;
        self.particles = (0..n)
            .map(|_| Particle {
                pose: random_free_pose(&self.map, &mut self.rng),
                weight: w,
            })
            .collect();
        self.restart();
    }

    fn restart(&mut self) {
        self.w_slow = Average::new(self.config.alpha_slow);
        self.w_fast = Average::new(self.config.alpha_fast);
        self.random_share = 0.0;
        self.force_update = true;
        self.effective = self.particles.len() as f64;
        self.converged = false;
        self.refresh_estimate();
    }

    /// Folds in the odometry pose (the robot's own dead reckoning) and, when the robot
    /// moved enough since the last update, the scan. True when the filter updated.
    pub fn update(&mut self, odom: Pose2, scan: &LaserScan) -> bool {
        let Some(last) = self.odom_at_update else {
            self.odom_at_update = Some(odom);
            if !self.force_update {
                return false;
            }
            return self.correct(scan);
        };
        let step = OdometryStep::between(last, odom);
        let turned = wrap_angle(odom.theta - last.theta).abs();
        let moved = step.trans >= self.config.update_min_d || turned >= self.config.update_min_a;
        if !moved && !self.force_update {
            return false;
        }
        if !step.is_still() {
            let std = motion::noise_std(&step, &self.config);
            for p in &mut self.particles {
                p.pose = motion::sample(p.pose, &step, std, &mut self.rng);
            }
        }
        self.odom_at_update = Some(odom);
        self.correct(scan)
    }

    /// Weighs the particles by `scan`, and resamples when the weights are lopsided.
    fn correct(&mut self, scan: &LaserScan) -> bool {
        self.force_update = false;
        let beams = Beams::pick(scan, self.config.max_beams);
        if beams.is_empty() || self.particles.is_empty() {
            return false;
        }
        let range = scan.range_max;
        if self.weigher.as_ref().is_none_or(|(r, _)| *r != range) {
            self.weigher = Some((range, Weigher::new(&self.map, &self.config, range)));
        }
        let (_, weigher) = self.weigher.as_mut().expect("built above");
        let map = &self.map;
        let logs: Vec<f64> = (self.particles.iter())
            .map(|p| weigher.log_likelihood(map, p.pose, &beams))
            .collect();
        let n_beams = beams.len() as f64;
        // Augmented MCL's w_avg (table 8.3, line 8), per beam (the n-th root of each
        // particle's likelihood) so that it does not depend on how many beams are weighed.
        let w_avg = logs.iter().map(|l| (l / n_beams).exp()).sum::<f64>() / logs.len() as f64;
        self.w_slow.add(w_avg);
        self.w_fast.add(w_avg);
        let top = logs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let mut total = 0.0;
        for (p, l) in self.particles.iter_mut().zip(&logs) {
            // Bayes: the prior weight times the likelihood, scaled by the best so nothing
            // underflows.
            p.weight *= (l - top).exp();
            total += p.weight;
        }
        if !(total > 0.0 && total.is_finite()) {
            let w = 1.0 / self.particles.len() as f64;
            self.particles.iter_mut().for_each(|p| p.weight = w);
        } else {
            self.particles.iter_mut().for_each(|p| p.weight /= total);
        }
        let weights: Vec<f64> = self.particles.iter().map(|p| p.weight).collect();
        self.effective = resample::effective_sample_size(&weights);
        // The estimate comes from the weighted set, before resampling: resampling only adds
        // noise to it (Probabilistic Robotics 4.3.4), and a random particle added below has
        // not yet met a scan, so it must not pull the estimate until one has weighed it.
        self.force_update = false;
        self.refresh_estimate();
        // Table 8.3, line 13: random particles while the scans fit worse lately than they
        // used to.
        let (slow, fast) = (self.w_slow.value(), self.w_fast.value());
        self.random_share = if slow > 0.0 && self.config.alpha_slow > 0.0 {
            (1.0 - fast / slow).max(0.0)
        } else {
            0.0
        };
        // Resample when the weights have grown lopsided, or to let random particles in: a
        // kidnapped robot's particles fit equally badly, so their weights stay even.
        let lopsided = self.effective < self.config.resample_ess * self.particles.len() as f64;
        if lopsided || self.random_share > 0.0 {
            self.resample(&weights);
        }
        self.updates += 1;
        true
    }

    /// Resampling with KLD-sampling's count (table 8.4): a low-variance draw of the most
    /// particles allowed (table 4.4), taken in random order one by one, each replaced by a
    /// random particle with augmented MCL's probability (table 8.3), until the new set
    /// is as large as the bins it occupies ask for. Random particles count in the bins, so
    /// a filter that is looking for its robot grows its set.
    fn resample(&mut self, weights: &[f64]) {
        let c = &self.config;
        let (size, angle) = (c.bin_size, c.bin_angle_deg.to_radians());
        let (least, most) = (c.min_particles as usize, c.max_particles as usize);
        let mut pool = resample::low_variance(weights, most, &mut self.rng);
        pool.shuffle(&mut self.rng);
        let mut bins = std::collections::HashSet::new();
        let old = std::mem::take(&mut self.particles);
        let mut poses = Vec::with_capacity(most);
        for i in pool {
            let random = self.random_share > 0.0 && self.rng.random::<f64>() < self.random_share;
            let pose = if random {
                random_free_pose(&self.map, &mut self.rng)
            } else {
                old[i].pose
            };
            bins.insert(cluster::bin_of(pose, size, angle));
            poses.push(pose);
            let n = poses.len();
            if n >= least && n >= resample::kld_bound(bins.len(), c.kld_err, c.kld_z) {
                break;
            }
        }
        let w = 1.0 / poses.len() as f64;
        self.particles = (poses.into_iter())
            .map(|pose| Particle { pose, weight: w })
            .collect();
        // `effective` stays the weighing's: after resampling it would always equal the
        // count, and say nothing.
    }

    fn refresh_estimate(&mut self) {
        let poses: Vec<Pose2> = self.particles.iter().map(|p| p.pose).collect();
        let weights: Vec<f64> = self.particles.iter().map(|p| p.weight).collect();
        let c = &self.config;
        self.estimate =
            cluster::estimate(&poses, &weights, c.bin_size, c.bin_angle_deg.to_radians());
        // Converged: one cluster holds the weight and is tight. It is left only well past
        // those bounds (3/4 of the weight, twice the spread), so that the few random
        // particles augmented MCL adds do not make the status flicker.
        // Only a scan can tell: particles just placed have not met one yet.
        let (weight, spread) = (self.estimate.weight, self.position_std());
        let (w, sd) = (c.converged_weight, c.converged_std);
        self.converged = if self.force_update {
            false
        } else if self.converged {
            weight >= 0.75 * w && spread <= 2.0 * sd
        } else {
            weight >= w && spread <= sd
        };
    }

    /// The estimate now, given the odometry pose now: the estimate at the last update
    /// moved by what the odometry measured since (REP 105's map -> odom at work).
    pub fn pose(&self, odom: Pose2) -> Pose2 {
        let at = self.estimate.pose;
        let Some(last) = self.odom_at_update else {
            return at;
        };
        // The odometry's motion since the update, in the robot's frame then.
        let (s, c) = last.theta.sin_cos();
        let (dx, dy) = (odom.x - last.x, odom.y - last.y);
        let local = Point2::new(c * dx + s * dy, -s * dx + c * dy);
        let here = at.transform_point(local);
        Pose2::new(
            here.x,
            here.y,
            wrap_angle(at.theta + odom.theta - last.theta),
        )
    }

    /// The covariance (x, y, θ) of the heaviest cluster.
    pub fn covariance(&self) -> Matrix3<f64> {
        self.estimate.covariance
    }

    /// The estimate's position standard deviation along its worst direction, metres.
    pub fn position_std(&self) -> f64 {
        let c = self
            .estimate
            .covariance
            .fixed_view::<2, 2>(0, 0)
            .into_owned();
        crate::slam::ellipse::axes(&c, 1.0).0
    }

    pub fn particles(&self) -> &[Particle] {
        &self.particles
    }

    pub fn status(&self) -> Status {
        Status {
            particles: self.particles.len(),
            effective: self.effective,
            cluster_weight: self.estimate.weight,
            clusters: self.estimate.clusters,
            converged: self.converged,
            random_share: self.random_share,
            updates: self.updates,
        }
    }

    pub fn config(&self) -> &LocalizationConfig {
        &self.config
    }
}

/// A pose on a known free cell, anywhere in it, heading at random.
fn random_free_pose(map: &KnownMap, rng: &mut ChaCha8Rng) -> Pose2 {
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
struct Average {
    alpha: f64,
    raw: f64,
    /// (1 - α)^k.
    decay: f64,
}

impl Average {
    fn new(alpha: f64) -> Self {
        Self {
            alpha,
            raw: 0.0,
            decay: 1.0,
        }
    }

    fn add(&mut self, x: f64) {
        self.raw += self.alpha * (x - self.raw);
        self.decay *= 1.0 - self.alpha;
    }

    fn value(&self) -> f64 {
        let weight = 1.0 - self.decay;
        if weight > 0.0 { self.raw / weight } else { 0.0 }
    }
}
