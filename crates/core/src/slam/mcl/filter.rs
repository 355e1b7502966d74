//! The particle filter itself; see the module comment in `mod.rs`.

use super::cluster::{self, CloudEstimate};
use super::config::{LocalizationConfig, SensorModel};
use super::known_map::KnownMap;
use super::motion::{self, OdometryStep};
use super::recovery::{Average, random_free_pose};
use super::resample;
use super::rivals::{self, RecentScans};
use super::sensor::{Beams, Weigher};
pub use super::status::{Phase, Status};
use crate::data::LaserScan;
use crate::geometry::{Pose2, wrap_angle};
use nalgebra::Matrix3;
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use std::sync::Arc;

mod view;

/// One hypothesis of where the robot is, with its normalised weight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Particle {
    pub pose: Pose2,
    pub weight: f64,
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
    /// Lost after having been localised (see `Phase::Lost`), until localised again.
    lost: bool,
    /// The share of the last scan the map explains at the estimate.
    agreement: Option<f64>,
    /// The update at which the map was last searched for rivals of the estimate.
    rivals_checked: Option<u64>,
    /// The recent scans a rival is judged by.
    recent: RecentScans,
    /// Looking for the robot anywhere (global localisation, or lost): only then is the
    /// map searched for rivals; a pose the user placed is taken as told.
    searching: bool,
    effective: f64,
    updates: u64,
}

/// A beam agrees with the map when its end lies this near a mapped obstacle (AMCL's
/// `beam_skip_distance`, 0.5 m).
const AGREE_NEAR: f64 = 0.5;
/// Localised needs at least this share of the scan's beams to agree with the map at the
/// estimate: the map must explain most of what the lidar sees there (a wrong pose in a
/// look-alike room leaves walls where the scan found none).
const AGREE_LEAST: f64 = 0.5;
/// Lost when the recent fit w_fast falls under this share of the long-run w_slow
/// (Probabilistic Robotics table 8.3, line 13: augmented MCL then replaces at least every
/// second resampled particle by a random one).
const LOST_RATIO: f64 = 0.5;
/// Updates between two searches for rivals (0.5 m or 0.5 rad of motion by default).
const RECHECK_UPDATES: u64 = 5;
/// The share of a scan's beams that must hit something before it may judge whether the
/// map explains the scan (navdeck's: 12 of AMCL's 60 beams).
const JUDGED_SHARE: f64 = 0.2;

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
            w_slow: Average::new(config.recovery.alpha_slow),
            w_fast: Average::new(config.recovery.alpha_fast),
            random_share: 0.0,
            odom_at_update: None,
            force_update: true,
            estimate: CloudEstimate {
                pose: Pose2::default(),
                covariance: Matrix3::identity(),
                weight: 0.0,
                clusters: 0,
                hypotheses: Vec::new(),
            },
            converged: false,
            lost: false,
            agreement: None,
            rivals_checked: None,
            recent: RecentScans::default(),
            searching: false,
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
        let n = self.config.particles.max_particles as usize;
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
        self.searching = false;
    }

    /// Global localisation: particles spread evenly over the map's free space, headings
    /// at random, as many as the global phase allows (`global_max_particles`).
    pub fn init_global(&mut self) {
        self.searching = true;
        let n = self.most_particles();
        let w = 1.0 / n as f64;
        self.particles = (0..n)
            .map(|_| Particle {
                pose: random_free_pose(&self.map, &mut self.rng),
                weight: w,
            })
            .collect();
        self.restart();
        self.searching = true;
    }

    fn restart(&mut self) {
        self.w_slow = Average::new(self.config.recovery.alpha_slow);
        self.w_fast = Average::new(self.config.recovery.alpha_fast);
        self.random_share = 0.0;
        self.force_update = true;
        self.effective = self.particles.len() as f64;
        self.converged = false;
        self.lost = false;
        self.agreement = None;
        self.recent.clear();
        self.refresh_estimate();
    }

    /// KLD-sampling's maximum now: the generous global one while the filter looks for
    /// the robot, AMCL's `max_particles` while it tracks.
    fn most_particles(&self) -> usize {
        let c = &self.config.particles;
        if self.converged || !self.searching {
            c.max_particles as usize
        } else {
            c.global_max_particles.max(c.max_particles) as usize
        }
    }

    /// Folds in the odometry pose (the robot's own dead reckoning) and, when the robot
    /// moved enough since the last update, the scan. True when the filter updated.
    pub fn update(&mut self, odom: Pose2, scan: &LaserScan) -> bool {
        let Some(last) = self.odom_at_update else {
            self.odom_at_update = Some(odom);
            if !self.force_update {
                return false;
            }
            return self.correct(scan, None);
        };
        let step = OdometryStep::between(last, odom);
        let turned = wrap_angle(odom.theta - last.theta).abs();
        let moved = step.trans >= self.config.schedule.update_min_d
            || turned >= self.config.schedule.update_min_a;
        if !moved && !self.force_update {
            return false;
        }
        if !step.is_still() {
            let std = motion::noise_std(&step, &self.config.motion);
            for p in &mut self.particles {
                p.pose = motion::sample(p.pose, &step, std, &mut self.rng);
            }
        }
        self.odom_at_update = Some(odom);
        // Where the estimate should be now, had the robot moved only as the odometry says.
        self.correct(scan, Some(self.estimate.pose.compose(last.between(odom))))
    }

    /// Weighs the particles by `scan`, and resamples when the weights are lopsided.
    fn correct(&mut self, scan: &LaserScan, expected: Option<Pose2>) -> bool {
        self.force_update = false;
        let beams = Beams::pick(scan, self.config.measurement.max_beams);
        if beams.is_empty() || self.particles.is_empty() {
            return false;
        }
        let range = scan.range_max;
        if self.weigher.as_ref().is_none_or(|(r, _)| *r != range) {
            self.weigher = Some((
                range,
                Weigher::new(&self.map, &self.config.measurement, range),
            ));
        }
        let (_, weigher) = self.weigher.as_mut().expect("built above");
        let map = &self.map;
        let logs: Vec<f64> = (self.particles.iter())
            .map(|p| weigher.log_likelihood(map, p.pose, &beams))
            .collect();
        // The likelihood field skips readings at the maximum range (table 6.3, line 4): in
        // a room wider than the lidar's reach few beams or none are weighed. A scan whose
        // hits are that few (or on something the map lacks, a far block on the floor)
        // cannot judge whether the map explains it: it must not call the filter lost or
        // bring in rivals, which would fit it everywhere alike.
        let hits = beams
            .ranges
            .iter()
            .filter(|&&r| r < beams.max_range)
            .count();
        let judged = hits as f64 >= JUDGED_SHARE * beams.len() as f64;
        let weighed = match self.config.measurement.model {
            SensorModel::LikelihoodField => hits,
            SensorModel::Beam => beams.len(),
        };
        // Augmented MCL's w_avg (table 8.3, line 8), per beam weighed (the n-th root of
        // each particle's likelihood), so that it does not depend on how many were.
        if weighed > 0 {
            let n = weighed as f64;
            let w_avg = logs.iter().map(|l| (l / n).exp()).sum::<f64>() / logs.len() as f64;
            self.w_slow.add(w_avg);
            self.w_fast.add(w_avg);
        }
        let top = logs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        // Tracking takes the whole likelihood; looking for the robot, a power of it.
        let power = if self.converged || !self.searching {
            1.0
        } else {
            let prior: Vec<f64> = self.particles.iter().map(|p| p.weight).collect();
            resample::tempering(&prior, &logs, top, self.config.schedule.resample_ess)
        };
        let mut total = 0.0;
        for (p, l) in self.particles.iter_mut().zip(&logs) {
            // Bayes: the prior weight times the likelihood (to `power`), scaled by the best
            // so nothing underflows.
            p.weight *= (power * (l - top)).exp();
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
        // Table 8.3, line 13: random particles while the scans fit worse lately than they
        // used to.
        let (slow, fast) = (self.w_slow.value(), self.w_fast.value());
        self.random_share = if slow > 0.0 && self.config.recovery.alpha_slow > 0.0 {
            (1.0 - fast / slow).max(0.0)
        } else {
            0.0
        };
        // Lost: the scans fit much worse lately than they used to, or the map no longer
        // explains the scan at the estimate.
        let tracking = self.converged;
        let fell = tracking && 1.0 - self.random_share < LOST_RATIO;
        if fell {
            self.converged = false;
        }
        let was = self.converged;
        self.refresh_estimate();
        if judged {
            self.agreement = Weigher::agreement(&self.map, self.estimate.pose, &beams, AGREE_NEAR);
        }
        self.judge();
        let unexplained = judged && self.agreement.is_none_or(|a| a < AGREE_LEAST);
        // The heaviest cluster is now another place than the odometry carried the estimate
        // to: the robot was not where the filter said (carried off, or it had settled on a
        // look-alike).
        let jumped = expected.is_some_and(|e| !rivals::near(e, self.estimate.pose));
        if tracking && (fell || unexplained || jumped) {
            self.lost = true;
            self.searching = true;
            self.converged = false;
            // The scans before the robot was moved say nothing of where it is now.
            self.recent.clear();
        }
        if let Some(odom) = self.odom_at_update {
            self.recent.push(odom, beams.clone());
        }
        if judged && !self.converged && self.searching && self.updates > 0 && self.rivals_due() {
            // Still looking: the places that fit the scan as well as the estimate or
            // better, taken in as hypotheses, so that a truth the first particles missed
            // is weighed again (a correlative scan matcher's global search).
            self.has_rivals(&beams);
            self.refresh_estimate();
        }
        if self.converged && !was && self.searching && (!judged || self.has_rivals(&beams)) {
            // The rivals now show among the hypotheses; the filter is not localised.
            self.refresh_estimate();
            self.converged = false;
        }
        if self.converged && !was {
            // Localised: from here the averages measure how well the scans fit while
            // tracking, so that a kidnapping soon after shows as a fall from that fit, not
            // from the poorer fit of the search.
            self.w_slow = Average::new(self.config.recovery.alpha_slow);
            self.w_fast = Average::new(self.config.recovery.alpha_fast);
            self.lost = false;
        }
        // Resample when the weights have grown lopsided, or to let random particles in: a
        // kidnapped robot's particles fit equally badly, so their weights stay even.
        let lopsided =
            self.effective < self.config.schedule.resample_ess * self.particles.len() as f64;
        if lopsided || self.random_share > 0.0 {
            // The weights now, rivals taken back included.
            let weights: Vec<f64> = self.particles.iter().map(|p| p.weight).collect();
            self.resample(&weights);
        }
        self.updates += 1;
        true
    }

    /// Whether the scan fits elsewhere on the map nearly as well as at the estimate (see
    /// `rivals`); each such place is taken back as a hypothesis. Searched at most every
    /// `RECHECK_UPDATES` updates, so the robot has moved on between searches.
    fn has_rivals(&mut self, beams: &Beams) -> bool {
        if !self.rivals_due() {
            return true;
        }
        self.rivals_checked = Some(self.updates);
        let margin = rivals::margin(&self.config.measurement, beams);
        let (_, weigher) = self.weigher.as_mut().expect("built by the first scan");
        let (map, estimate) = (&self.map, self.estimate.pose);
        let odom = self.odom_at_update.unwrap_or_default();
        let found: Vec<Pose2> = rivals::rivals(map, weigher, beams, estimate, margin)
            .into_iter()
            .filter(|&r| !(self.recent).rule_out(map, weigher, odom, estimate, r, margin))
            .collect();
        if found.is_empty() {
            return false;
        }
        // Each rival as heavy as the estimate's cluster: this scan cannot tell them apart,
        // and the filter may have lost the rival only by the luck of its first particles.
        let each = (self.config.particles.min_particles as usize).max(1);
        let room = self.most_particles().saturating_sub(self.particles.len()) / each;
        let (sd, sa) = (
            self.config.particles.bin_size / 4.0,
            self.config.particles.bin_angle_deg.to_radians() / 2.0,
        );
        let w = self.estimate.weight / each as f64;
        for rival in found.into_iter().take(room.max(1)) {
            for _ in 0..each {
                let n = |rng: &mut ChaCha8Rng| -> f64 { StandardNormal.sample(rng) };
                let pose = Pose2::new(
                    rival.x + sd * n(&mut self.rng),
                    rival.y + sd * n(&mut self.rng),
                    wrap_angle(rival.theta + sa * n(&mut self.rng)),
                );
                self.particles.push(Particle { pose, weight: w });
            }
        }
        let total: f64 = self.particles.iter().map(|p| p.weight).sum();
        self.particles.iter_mut().for_each(|p| p.weight /= total);
        true
    }

    /// Whether `RECHECK_UPDATES` updates have passed since the last search for rivals.
    fn rivals_due(&self) -> bool {
        (self.rivals_checked).is_none_or(|u| self.updates >= u + RECHECK_UPDATES)
    }

    /// Resampling with KLD-sampling's count (table 8.4): a low-variance draw of the most
    /// particles allowed (table 4.4), taken in random order one by one, each replaced by a
    /// random particle with augmented MCL's probability (table 8.3), until the new set
    /// is as large as the bins it occupies ask for. Random particles count in the bins, so
    /// a filter that is looking for its robot grows its set.
    fn resample(&mut self, weights: &[f64]) {
        let c = &self.config.particles;
        let (size, angle) = (c.bin_size, c.bin_angle_deg.to_radians());
        let (least, most) = (c.min_particles as usize, self.most_particles());
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
        let c = &self.config.particles;
        self.estimate =
            cluster::estimate(&poses, &weights, c.bin_size, c.bin_angle_deg.to_radians());
        self.judge();
    }

    /// Decides whether the filter has converged, from the estimate and the agreement.
    fn judge(&mut self) {
        let c = &self.config.spread;
        // Converged: one cluster holds the weight and is tight. It is left only well past
        // those bounds (3/4 of the weight, twice the spread), so that the few random
        // particles augmented MCL adds do not make the status flicker.
        // Only a scan can tell: particles just placed have not met one yet.
        let (weight, spread) = (self.estimate.weight, self.position_std());
        let (w, sd) = (c.converged_weight, c.converged_std);
        let explained = self.agreement.is_some_and(|a| a >= AGREE_LEAST);
        self.converged = if self.force_update || !explained {
            false
        } else if self.converged {
            weight >= 0.75 * w && spread <= 2.0 * sd
        } else {
            weight >= w && spread <= sd
        };
    }

    pub fn config(&self) -> &LocalizationConfig {
        &self.config
    }
}
