//! `[localization]`: which estimator places the robot, and Monte-Carlo localisation's
//! settings. Names and defaults follow Nav2's AMCL where it has the same parameter, so a
//! user's `amcl:` block carries over; the sources are cited field by field.

use crate::data::check::{self, Invalid};
use serde::{Deserialize, Serialize};

mod section;

/// Which estimator's pose drives the robot.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Estimator {
    /// EKF-SLAM on marker landmarks (seed 001).
    #[default]
    Ekf,
    /// Monte-Carlo localisation with the lidar on a known map (seed 002).
    Mcl,
    /// Lidar SLAM: scan matching and a pose graph with loop closure, no markers or map
    /// needed (`[lidar_slam]`).
    Slam,
}

impl Estimator {
    pub fn label(self) -> &'static str {
        match self {
            Estimator::Ekf => "EKF-SLAM",
            Estimator::Mcl => "MCL",
            Estimator::Slam => "lidar SLAM",
        }
    }
}

impl std::str::FromStr for Estimator {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "ekf" => Ok(Estimator::Ekf),
            "mcl" => Ok(Estimator::Mcl),
            "slam" => Ok(Estimator::Slam),
            _ => Err(format!(
                "unknown estimator {s:?}: expected ekf, mcl or slam"
            )),
        }
    }
}

/// How a scan is weighed against the map.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SensorModel {
    /// Probabilistic Robotics 6.4: the distance from each beam's end to the nearest
    /// obstacle (AMCL's `likelihood_field`, its default).
    #[default]
    LikelihoodField,
    /// Probabilistic Robotics 6.3 and seed 002: each beam against the range ray-traced in
    /// the map (AMCL's `beam`).
    Beam,
}

/// `[localization]`: the estimator, and Monte-Carlo localisation's settings in groups that
/// each mean one thing. A config file writes them as one flat table, as AMCL's parameters
/// are (`alpha1 = 0.3` beside `max_particles = 3000`), and the groups share its keys out
/// (`#[serde(flatten)]`). Flattening lets a key no group has through, so a file's table is
/// checked first (`check_section`, in `config/section.rs`).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct LocalizationConfig {
    pub estimator: Estimator,
    #[serde(flatten)]
    pub particles: ParticleCount,
    #[serde(flatten)]
    pub motion: OdometryNoise,
    #[serde(flatten)]
    pub measurement: MeasurementModel,
    #[serde(flatten)]
    pub schedule: UpdateSchedule,
    #[serde(flatten)]
    pub recovery: Recovery,
    #[serde(flatten)]
    pub spread: Spread,
}

/// How many particles the filter keeps: KLD-sampling's bounds on the count, and the error,
/// quantile and histogram bins it sizes the set by (Fox 2003).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct ParticleCount {
    /// The particle count's bounds for KLD-sampling (AMCL `min_particles` 500,
    /// `max_particles` 2000). A global localisation spreads the most allowed over the free
    /// space, and a first scan can only keep hypotheses that were drawn: navdeck allows
    /// 5000, which found the robot within 30 s on 47 of 50 generated starts in the
    /// flat where 2000 found it on 42 (`navdeck tour --world maps/flat.yaml --estimator
    /// mcl --initial-pose unknown --random-start --sweep 1..50`).
    pub min_particles: u32,
    pub max_particles: u32,
    /// KLD-sampling's maximum while the filter looks for the robot (global localisation,
    /// or lost): the generous maximum of the global phase (Fox 2003: KLD-sampling sizes a
    /// spread-out belief's set by the bins it covers), 20,000, about one particle per
    /// KLD bin (0.5 m, 10°) over 140 m² of free space; KLD brings the count down to
    /// `max_particles` and below as the hypotheses gather.
    pub global_max_particles: u32,
    /// KLD-sampling: the bound on the error (AMCL `pf_err` 0.05) and the upper standard
    /// normal quantile z_(1-δ) (2.326 for δ = 0.01; Probabilistic Robotics table 8.4).
    pub kld_err: f64,
    pub kld_z: f64,
    /// KLD-sampling's histogram bins: metres and degrees (AMCL's 0.5 m, 10°).
    pub bin_size: f64,
    pub bin_angle_deg: f64,
}

impl Default for ParticleCount {
    fn default() -> Self {
        Self {
            min_particles: 500,
            max_particles: 5000,
            global_max_particles: 20_000,
            kld_err: 0.05,
            kld_z: 2.326,
            bin_size: 0.5,
            bin_angle_deg: 10.0,
        }
    }
}

/// The odometry motion model's noise: how much a particle's move strays from the wheels'.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct OdometryNoise {
    /// Odometry motion model noise (Probabilistic Robotics table 5.6, seed 002 "a1 - a4";
    /// AMCL `alpha1`..`alpha4`, 0.2 each): rotation from rotation, rotation from
    /// translation, translation from translation, translation from rotation.
    pub alpha1: f64,
    pub alpha2: f64,
    pub alpha3: f64,
    pub alpha4: f64,
}

impl Default for OdometryNoise {
    fn default() -> Self {
        Self {
            alpha1: 0.2,
            alpha2: 0.2,
            alpha3: 0.2,
            alpha4: 0.2,
        }
    }
}

/// The measurement model: how a scan is weighed against the map from a particle's pose.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct MeasurementModel {
    pub model: SensorModel,
    /// Mixture weights of the measurement model (Probabilistic Robotics 6.3; AMCL `z_hit`
    /// 0.5, `z_short` 0.05, `z_max` 0.05, `z_rand` 0.5).
    pub z_hit: f64,
    pub z_short: f64,
    pub z_max: f64,
    pub z_rand: f64,
    /// Standard deviation of a hit, metres (AMCL `sigma_hit` 0.2).
    pub sigma_hit: f64,
    /// Rate of the short-reading exponential, 1/m (AMCL `lambda_short` 0.1).
    pub lambda_short: f64,
    /// Distances to obstacles in the likelihood field stop growing here, metres (AMCL
    /// `laser_likelihood_max_dist` 2.0).
    pub likelihood_max_dist: f64,
    /// Beams of each scan weighed, evenly spread (AMCL `max_beams` 60; seed 002 used 8).
    pub max_beams: u32,
}

impl Default for MeasurementModel {
    fn default() -> Self {
        Self {
            model: SensorModel::LikelihoodField,
            z_hit: 0.5,
            z_short: 0.05,
            z_max: 0.05,
            z_rand: 0.5,
            sigma_hit: 0.2,
            lambda_short: 0.1,
            likelihood_max_dist: 2.0,
            max_beams: 60,
        }
    }
}

/// When the filter updates with a scan, and when it resamples.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct UpdateSchedule {
    /// The filter updates after the robot moved this far (m) or turned this much (rad).
    /// AMCL's `update_min_d` 0.25 and `update_min_a` 0.2 spare a robot's CPU; an update
    /// here costs under a millisecond and seed 002 updated at every 10 Hz step, so navdeck
    /// updates every 0.1 m or 0.1 rad.
    pub update_min_d: f64,
    pub update_min_a: f64,
    /// Resample when the effective sample size falls below this fraction of the particle
    /// count (Probabilistic Robotics 4.3.4; 0.5 is the usual choice).
    pub resample_ess: f64,
}

impl Default for UpdateSchedule {
    fn default() -> Self {
        Self {
            update_min_d: 0.1,
            update_min_a: 0.1,
            resample_ess: 0.5,
        }
    }
}

/// Recovery from a lost or kidnapped robot: augmented MCL's random particles.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Recovery {
    /// Augmented MCL's averages of the measurement likelihood (Probabilistic Robotics
    /// table 8.3; AMCL `recovery_alpha_slow` 0.001, `recovery_alpha_fast` 0.1 as its docs
    /// suggest). Both 0 turn random particles off.
    pub alpha_slow: f64,
    pub alpha_fast: f64,
}

impl Default for Recovery {
    fn default() -> Self {
        Self {
            alpha_slow: 0.001,
            alpha_fast: 0.1,
        }
    }
}

/// How spread the particles are: round a pose the user gives at the start, and round the
/// estimate once it counts as converged.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Spread {
    /// Spread of the particles around a given initial pose: metres and degrees (AMCL's
    /// initial covariance 0.5 m², (π/12)²: 0.71 m and 15°, here tighter for a pose the user
    /// places on the map).
    pub initial_std: f64,
    pub initial_std_deg: f64,
    /// The estimate has converged when its cluster holds this share of the weight and
    /// the cluster's position spreads less than this (a standard deviation, metres).
    pub converged_weight: f64,
    pub converged_std: f64,
}

impl Default for Spread {
    fn default() -> Self {
        Self {
            initial_std: 0.25,
            initial_std_deg: 10.0,
            converged_weight: 0.9,
            converged_std: 0.25,
        }
    }
}

impl LocalizationConfig {
    /// Checks what the parser cannot.
    pub fn validate(&self) -> Result<(), Invalid> {
        let (p, m, s) = (&self.particles, &self.motion, &self.measurement);
        let (u, r, sp) = (&self.schedule, &self.recovery, &self.spread);
        check::counts_within(&[
            ("min_particles", u64::from(p.min_particles), 1, 100_000),
            ("max_particles", u64::from(p.max_particles), 1, 100_000),
            (
                "global_max_particles",
                u64::from(p.global_max_particles),
                1,
                200_000,
            ),
            ("max_beams", u64::from(s.max_beams), 1, 4096),
        ])?;
        if p.min_particles > p.max_particles {
            return Err((
                "min_particles",
                f64::from(p.min_particles),
                format!("must not exceed max_particles ({})", p.max_particles).into(),
            ));
        }
        check::within(&[
            ("alpha1", m.alpha1, 0.0, 10.0),
            ("alpha2", m.alpha2, 0.0, 10.0),
            ("alpha3", m.alpha3, 0.0, 10.0),
            ("alpha4", m.alpha4, 0.0, 10.0),
            ("z_hit", s.z_hit, 0.0, 1.0),
            ("z_short", s.z_short, 0.0, 1.0),
            ("z_max", s.z_max, 0.0, 1.0),
            ("z_rand", s.z_rand, 0.0, 1.0),
            ("sigma_hit", s.sigma_hit, 0.001, 10.0),
            ("lambda_short", s.lambda_short, 0.001, 100.0),
            ("likelihood_max_dist", s.likelihood_max_dist, 0.01, 100.0),
            ("update_min_d", u.update_min_d, 0.0, 10.0),
            ("update_min_a", u.update_min_a, 0.0, std::f64::consts::PI),
            ("resample_ess", u.resample_ess, 0.0, 1.0),
            ("kld_err", p.kld_err, 0.001, 1.0),
            ("kld_z", p.kld_z, 0.0, 10.0),
            ("bin_size", p.bin_size, 0.01, 10.0),
            ("bin_angle_deg", p.bin_angle_deg, 0.5, 180.0),
            ("alpha_slow", r.alpha_slow, 0.0, 1.0),
            ("alpha_fast", r.alpha_fast, 0.0, 1.0),
            ("initial_std", sp.initial_std, 0.0, 100.0),
            ("initial_std_deg", sp.initial_std_deg, 0.0, 180.0),
            ("converged_weight", sp.converged_weight, 0.01, 1.0),
            ("converged_std", sp.converged_std, 0.001, 100.0),
        ])?;
        if s.z_hit + s.z_rand <= 0.0 {
            return Err((
                "z_hit",
                s.z_hit,
                "z_hit and z_rand must not both be 0: every scan would weigh nothing".into(),
            ));
        }
        if r.alpha_slow > 0.0 && r.alpha_fast <= r.alpha_slow {
            return Err((
                "alpha_fast",
                r.alpha_fast,
                format!("must exceed alpha_slow ({})", r.alpha_slow).into(),
            ));
        }
        Ok(())
    }
}
