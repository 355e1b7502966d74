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
    let mut twin = Twin::new(World::default_arena(), &config, 11);
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
