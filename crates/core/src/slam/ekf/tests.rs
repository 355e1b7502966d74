//! The filter against hand-worked cases.

use super::*;
use crate::data::MarkerSighting;

fn filter(start_var: f64) -> EkfSlam {
    EkfSlam::new(
        Pose2::default(),
        Matrix3::from_diagonal_element(start_var),
        &SlamConfig::default(),
        0.11,
    )
}

fn sighting(id: u32, range: f64, bearing: f64) -> MarkerSighting {
    MarkerSighting { id, range, bearing }
}

#[test]
fn straight_prediction_moves_along_heading_and_grows_along_track_variance() {
    // A start uncertainty above the pose floor, so the floor does not act.
    let p0 = 1e-4;
    let mut f = filter(p0);
    f.predict(WheelTravel {
        left: 0.1,
        right: 0.1,
    });
    let p = f.pose();
    assert!((p.x - 0.1).abs() < 1e-15 && p.y == 0.0 && p.theta == 0.0);
    // Hand-worked: G = [[1, 0, 0], [0, 1, l], [0, 0, 1]] and
    // V = [[.5, .5], [-l/2w, l/2w], [-1/w, 1/w]] with l = 0.1, w = 0.11,
    // Q = diag(s^2, s^2), s = 0.1 * (4 deg in rad) / 2 pi.
    let s = 0.1 * 4f64.to_radians() / std::f64::consts::TAU;
    let c = f.pose_covariance();
    assert!((c[(0, 0)] - (p0 + 0.5 * s * s)).abs() < 1e-18);
    let k = 0.1 / (2.0 * 0.11);
    assert!((c[(1, 1)] - (p0 + 0.01 * p0 + 2.0 * k * k * s * s)).abs() < 1e-18);
    assert!((c[(2, 2)] - (p0 + 2.0 * s * s / (0.11 * 0.11))).abs() < 1e-15);
}

#[test]
fn a_known_start_and_rank_two_wheel_noise_still_give_a_definite_pose_block() {
    // Two wheels' noise spans two of three directions: without the floor this block
    // would be singular, and its inverse (for NEES) meaningless.
    let mut f = filter(0.0);
    f.predict(WheelTravel {
        left: 0.1,
        right: 0.1,
    });
    let (sp, sh) = POSE_STD_FLOOR;
    let d = Matrix3::from_diagonal(&Vector3::new(1.0 / sp, 1.0 / sp, 1.0 / sh));
    let scaled = d * f.pose_covariance() * d;
    assert!(scaled.symmetric_eigenvalues().min() >= 1.0 - 1e-9);
    assert!(f.pose_covariance().cholesky().is_some());
}

#[test]
fn standing_still_under_thousands_of_sightings_keeps_the_covariance_definite() {
    let mut f = filter(0.0);
    let marks = [(1, 1.0, 0.3), (2, 1.5, -0.8), (3, 2.0, 2.0), (4, 0.7, -2.5)];
    for round in 0..3000 {
        for &(id, range, bearing) in &marks {
            // Deterministic jitter within the sensor's noise.
            let j = ((round * 7 + id as usize * 13) % 11) as f64 / 10.0 - 0.5;
            f.correct(sighting(id, range + 0.02 * j, bearing + 0.01 * j));
        }
        f.predict(WheelTravel::default());
    }
    let full = f.covariance();
    let smallest = full.clone().symmetric_eigenvalues().min();
    assert!(smallest > 0.0, "smallest eigenvalue {smallest:e}");
    assert!(full.cholesky().is_some());
    assert_eq!(f.rejected(), 0, "a calm filter gates out nothing");
}

#[test]
fn arc_prediction_matches_odometry() {
    let mut f = filter(0.0);
    let w = WheelTravel {
        left: 0.05,
        right: 0.07,
    };
    f.predict(w);
    assert_eq!(f.pose(), predict_pose(Pose2::default(), w, 0.11));
}

#[test]
fn one_landmark_update_with_known_numbers() {
    // Robot certain at the origin; landmark sighted at 2 m dead ahead, then seen at 2.1 m.
    let config = SlamConfig {
        fixed_initial_variance: Some(0.5),
        ..SlamConfig::default()
    };
    let mut f = EkfSlam::new(Pose2::default(), Matrix3::zeros(), &config, 0.11);
    assert_eq!(f.correct(sighting(7, 2.0, 0.0)), Outcome::Added);
    let out = f.correct(sighting(7, 2.1, 0.0));
    // Hand-worked: the range row is H = [dx/r, dy/r] = [1, 0] on the landmark,
    // S = 0.5 + 0.01, K_x = 0.5 / 0.51, so x moves by 0.1 * 0.5 / 0.51.
    let l = f.landmark(7).unwrap();
    assert!((l.mean.x - (2.0 + 0.1 * 0.5 / 0.51)).abs() < 1e-12, "{l:?}");
    assert!((l.covariance[(0, 0)] - (0.5 - 0.25 / 0.51)).abs() < 1e-12);
    // d^2 = 0.1^2 / 0.51
    assert!(matches!(out, Outcome::Corrected(d2) if (d2 - 0.01 / 0.51).abs() < 1e-12));
    assert_eq!(l.sightings, 2);
}

#[test]
fn propagated_initial_uncertainty_follows_the_inverse_model() {
    let mut f = filter(0.0);
    f.correct(sighting(3, 2.0, std::f64::consts::FRAC_PI_2));
    let l = f.landmark(3).unwrap();
    assert!(l.mean.x.abs() < 1e-12 && (l.mean.y - 2.0).abs() < 1e-12);
    // Range noise lies along y, bearing noise (times the range) along x.
    let a = 4f64.to_radians();
    assert!((l.covariance[(1, 1)] - 0.01).abs() < 1e-12);
    assert!((l.covariance[(0, 0)] - 4.0 * a * a).abs() < 1e-12);
}

#[test]
fn outliers_beyond_the_gate_are_rejected_and_counted() {
    let mut f = filter(0.0);
    f.correct(sighting(9, 1.0, 0.0));
    for _ in 0..20 {
        f.correct(sighting(9, 1.0, 0.0));
    }
    assert!(matches!(
        f.correct(sighting(9, 3.0, 0.0)),
        Outcome::Rejected(_)
    ));
    assert_eq!(f.rejected(), 1);
    assert_eq!(f.correct(sighting(9, f64::NAN, 0.0)), Outcome::Invalid);
}

#[test]
fn min_sightings_delays_entry() {
    let config = SlamConfig {
        min_sightings: 3,
        ..SlamConfig::default()
    };
    let mut f = EkfSlam::new(Pose2::default(), Matrix3::zeros(), &config, 0.11);
    assert_eq!(f.correct(sighting(1, 1.0, 0.0)), Outcome::Pending);
    assert_eq!(f.correct(sighting(1, 1.0, 0.0)), Outcome::Pending);
    assert_eq!(f.correct(sighting(1, 1.0, 0.0)), Outcome::Added);
    assert_eq!(f.landmark_count(), 1);
}

#[test]
fn a_forgotten_landmark_leaves_the_others_as_they_were_and_comes_back_afresh() {
    let mut f = filter(0.0);
    f.correct(sighting(1, 1.0, 0.0));
    f.correct(sighting(2, 2.0, 0.5));
    f.correct(sighting(3, 1.5, -0.5));
    let (before2, before3) = (f.landmark(2).unwrap(), f.landmark(3).unwrap());
    assert!(f.forget(2));
    assert!(!f.forget(2), "already gone");
    assert_eq!(f.landmark_count(), 2);
    assert!(f.landmark(2).is_none());
    assert_eq!(f.landmark(3), Some(before3));
    assert_eq!(f.covariance().nrows(), 3 + 2 * 2);
    // Seen somewhere else now: a new landmark, not a rejected sighting.
    assert_eq!(f.correct(sighting(2, 1.0, 2.5)), Outcome::Added);
    assert!(f.landmark(2).unwrap().mean.distance(before2.mean) > 1.0);
    assert_eq!(f.rejected(), 0);
}
