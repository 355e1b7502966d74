//! The odometry motion model, sampled (Probabilistic Robotics table 5.6; seed 002 "odometry
//! motion model", a1 - a4): the relative motion between two odometry poses split into a
//! turn, a straight and a turn, each corrupted by noise that grows with the motion.

use super::config::OdometryNoise;
use crate::geometry::{Pose2, wrap_angle};
use rand::Rng;
use rand_distr::{Distribution, StandardNormal};

/// Below this translation the first turn is taken as zero: the heading of a tiny step
/// is noise (AMCL's 0.01 m).
const NO_STEP: f64 = 0.01;

/// The motion between two odometry poses, as turn, straight, turn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OdometryStep {
    pub rot1: f64,
    pub trans: f64,
    pub rot2: f64,
}

impl OdometryStep {
    /// Probabilistic Robotics table 5.6, lines 2-4.
    pub fn between(from: Pose2, to: Pose2) -> Self {
        let (dx, dy) = (to.x - from.x, to.y - from.y);
        let trans = dx.hypot(dy);
        let rot1 = if trans < NO_STEP {
            0.0
        } else {
            wrap_angle(dy.atan2(dx) - from.theta)
        };
        let rot2 = wrap_angle(to.theta - from.theta - rot1);
        Self { rot1, trans, rot2 }
    }

    pub fn is_still(&self) -> bool {
        self.trans == 0.0 && self.rot1 == 0.0 && self.rot2 == 0.0
    }
}

/// A turn's size for the noise: driving backwards is a turn of π plus a small one, and
/// only the small one is noisy (AMCL's treatment of reverse motion).
fn turn_for_noise(rot: f64) -> f64 {
    rot.abs().min((std::f64::consts::PI - rot.abs()).abs())
}

/// The noise each part of `step` gets: standard deviations of rot1, trans, rot2
/// (Probabilistic Robotics table 5.6, lines 5-7, with the variances a1 δ² + a2 δ²
/// as AMCL writes them).
pub fn noise_std(step: &OdometryStep, c: &OdometryNoise) -> (f64, f64, f64) {
    let (r1, r2) = (turn_for_noise(step.rot1), turn_for_noise(step.rot2));
    let t2 = step.trans * step.trans;
    (
        (c.alpha1 * r1 * r1 + c.alpha2 * t2).sqrt(),
        (c.alpha3 * t2 + c.alpha4 * (r1 * r1 + r2 * r2)).sqrt(),
        (c.alpha1 * r2 * r2 + c.alpha2 * t2).sqrt(),
    )
}

/// `pose` moved by `step` with sampled noise (Probabilistic Robotics table 5.6, lines 5-10).
pub fn sample(pose: Pose2, step: &OdometryStep, std: (f64, f64, f64), rng: &mut impl Rng) -> Pose2 {
    let mut normal = |s: f64| -> f64 {
        let n: f64 = StandardNormal.sample(rng);
        s * n
    };
    let rot1 = step.rot1 - normal(std.0);
    let trans = step.trans - normal(std.1);
    let rot2 = step.rot2 - normal(std.2);
    let heading = pose.theta + rot1;
    Pose2::new(
        pose.x + trans * heading.cos(),
        pose.y + trans * heading.sin(),
        wrap_angle(heading + rot2),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;
    use std::f64::consts::FRAC_PI_2;

    fn quiet() -> OdometryNoise {
        OdometryNoise {
            alpha1: 0.0,
            alpha2: 0.0,
            alpha3: 0.0,
            alpha4: 0.0,
        }
    }

    #[test]
    fn a_step_splits_into_turn_straight_turn() {
        // From the origin facing +x to (1, 1) facing +y: turn 45°, drive √2, turn 45°.
        let s = OdometryStep::between(Pose2::new(0.0, 0.0, 0.0), Pose2::new(1.0, 1.0, FRAC_PI_2));
        assert!((s.rot1 - FRAC_PI_2 / 2.0).abs() < 1e-12);
        assert!((s.trans - 2f64.sqrt()).abs() < 1e-12);
        assert!((s.rot2 - FRAC_PI_2 / 2.0).abs() < 1e-12);
    }

    #[test]
    fn without_noise_a_particle_moves_as_the_odometry_did_in_its_own_frame() {
        // Odometry drove 1 m ahead and turned left; a particle facing +y at (2, 3) ends at
        // (2, 4) facing -x.
        let s = OdometryStep::between(Pose2::new(5.0, 5.0, 0.0), Pose2::new(6.0, 5.0, FRAC_PI_2));
        let std = noise_std(&s, &quiet());
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let p = sample(Pose2::new(2.0, 3.0, FRAC_PI_2), &s, std, &mut rng);
        assert!((p.x - 2.0).abs() < 1e-12 && (p.y - 4.0).abs() < 1e-12);
        assert!((p.theta - std::f64::consts::PI).abs() < 1e-12);
    }

    #[test]
    fn noise_grows_with_the_motion_as_the_alphas_say() {
        let c = OdometryNoise::default();
        // A straight 1 m: rotation std sqrt(a2) = 0.447, translation std sqrt(a3) = 0.447.
        let s = OdometryStep::between(Pose2::default(), Pose2::new(1.0, 0.0, 0.0));
        let (r1, t, r2) = noise_std(&s, &c);
        assert!((r1 - 0.2f64.sqrt()).abs() < 1e-12 && (r2 - r1).abs() < 1e-12);
        assert!((t - 0.2f64.sqrt()).abs() < 1e-12);
        // Driving backwards 1 m is as noisy as forwards, not a half-turn's worth.
        let back = OdometryStep::between(Pose2::default(), Pose2::new(-1.0, 0.0, 0.0));
        let (b1, bt, _) = noise_std(&back, &c);
        assert!((b1 - r1).abs() < 1e-9 && (bt - t).abs() < 1e-9);
    }

    #[test]
    fn sampled_translation_has_the_modelled_spread() {
        // Only a3: the straight's length varies with std sqrt(a3) * 0.5 = 0.05 m.
        let c = OdometryNoise {
            alpha3: 0.01,
            ..quiet()
        };
        let s = OdometryStep::between(Pose2::default(), Pose2::new(0.5, 0.0, 0.0));
        let std = noise_std(&s, &c);
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let n = 20_000;
        let xs: Vec<f64> = (0..n)
            .map(|_| sample(Pose2::default(), &s, std, &mut rng).x)
            .collect();
        let mean = xs.iter().sum::<f64>() / n as f64;
        let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
        assert!((mean - 0.5).abs() < 0.002, "{mean}");
        assert!((var.sqrt() - 0.05).abs() < 0.002, "{}", var.sqrt());
    }
}
