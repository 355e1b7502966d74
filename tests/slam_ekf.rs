//! EKF-SLAM fed by the twin over a long run: the covariance stays symmetric and positive
//! semi-definite, and the estimate stays near the truth.

use nalgebra::Matrix3;
use navdeck::config::Config;
use navdeck::geometry::Twist;
use navdeck::sim::{Twin, World};
use navdeck::slam::ekf::EkfSlam;

#[test]
fn an_hour_of_driving_keeps_sigma_symmetric_and_psd() {
    let config = Config::default();
    let mut twin = Twin::new(World::default_arena(), &config.robot, &config.sim, 11);
    let mut ekf = EkfSlam::new(
        twin.pose(),
        Matrix3::from_diagonal_element(1e-6),
        &config.slam,
        config.robot.track,
    );
    let period = config.robot.control_period;
    let mut worst = 0.0f64;
    for step in 0..36_000 {
        // A slow circle, reversing now and then so the robot does not stay against a wall.
        let sign = if (step / 600) % 2 == 0 { 1.0 } else { -1.0 };
        twin.set_command(Twist::new(0.1 * sign, 0.25));
        twin.step(period);
        let frame = twin.take_frame();
        if let Some(w) = frame.wheels {
            ekf.predict(w);
        }
        for s in frame.sightings.unwrap_or_default() {
            ekf.correct(s);
        }
        let truth = twin.pose();
        let est = ekf.pose();
        worst = worst.max((truth.x - est.x).hypot(truth.y - est.y));
        if step % 6_000 == 5_999 {
            let sigma = ekf.covariance();
            let eig = sigma.symmetric_eigenvalues();
            let min = eig.min();
            assert!(min > -1e-9, "negative eigenvalue {min} at step {step}");
        }
    }
    assert!(
        ekf.landmark_count() > 20,
        "saw only {}",
        ekf.landmark_count()
    );
    assert!(worst < 0.3, "estimate strayed {worst:.3} m from the truth");
}

/// Seed 001 claims +-5 cm and +-3 degrees; the filter must do that in its own arena, and
/// its confidence must be honest (mean NEES in the 95 % band of a 3-dof chi-square).
#[test]
fn scripted_five_minute_loop_meets_seed_accuracy_with_consistent_covariance() {
    use navdeck::keymap::parse_key_sequence;
    use navdeck::pilot::estimate::NEES_BAND_3DOF;
    use navdeck::session::{LinkChoice, Session, SessionSpec};
    let loop_keys = format!("{}{}", "w".repeat(30), "a".repeat(9)).repeat(77);
    let keys = parse_key_sequence(&loop_keys).unwrap();
    for seed in [1, 2] {
        let spec = SessionSpec {
            world: None,
            seed,
            start: None,
            config: None,
            keymap: None,
            link: LinkChoice::Sim,
            localize: Default::default(),
        };
        let mut app = Session::load(&spec).unwrap().into_app(0.0);
        let r = navdeck::runners::headless::run(&mut app, &keys, 10.0);
        assert!(r.sim_time > 300.0);
        assert_eq!(r.collisions, Some(0), "the loop should stay clear of walls");
        let (pos, head, nees) = (
            r.score.position_rmse.unwrap(),
            r.score.heading_rmse_deg.unwrap(),
            r.score.mean_nees.unwrap(),
        );
        assert!(pos < 0.05, "seed {seed}: position RMSE {pos:.4} m");
        let max = r.score.position_max_error.unwrap();
        assert!(
            max >= pos && max < 0.3,
            "seed {seed}: largest error {max:.4} m"
        );
        assert!(head < 3.0, "seed {seed}: heading RMSE {head:.3} deg");
        assert!(
            nees > NEES_BAND_3DOF.0 && nees < NEES_BAND_3DOF.1,
            "seed {seed}: mean NEES {nees:.3}"
        );
        assert!(r.landmarks >= 20);
    }
}

/// A plan-and-follow from a standing start: the pose covariance starts at zero and the
/// wheels' noise spans only two directions, which once made NEES meaningless (about
/// -2e15). It must be finite and in the band, and the filter must keep gating sanely.
#[test]
fn a_standing_start_then_goto_keeps_nees_finite_and_in_band() {
    use navdeck::keymap::parse_key_sequence;
    use navdeck::pilot::estimate::NEES_BAND_3DOF;
    use navdeck::session::{LinkChoice, Session, SessionSpec};
    let keys = parse_key_sequence(":goto 1.2 1.2<enter>p").unwrap();
    for seed in [1, 2, 3, 7] {
        let spec = SessionSpec {
            world: None,
            seed,
            start: None,
            config: None,
            keymap: None,
            link: LinkChoice::Sim,
            localize: Default::default(),
        };
        let mut app = Session::load(&spec).unwrap().into_app(0.0);
        let r = navdeck::runners::headless::run(&mut app, &keys, 10.0);
        let nees = r.score.mean_nees.unwrap();
        assert!(
            nees.is_finite() && nees > NEES_BAND_3DOF.0 && nees < NEES_BAND_3DOF.1,
            "seed {seed}: mean NEES {nees}"
        );
        assert!(
            r.rejected_sightings < 10,
            "seed {seed}: {}",
            r.rejected_sightings
        );
        let smallest = app
            .pilot()
            .slam()
            .covariance()
            .symmetric_eigenvalues()
            .min();
        assert!(
            smallest > 0.0,
            "seed {seed}: smallest eigenvalue {smallest:e}"
        );
    }
}
