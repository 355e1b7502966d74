use super::*;

fn fed(sensor: Sensor, from: f64, to: f64, every: f64, h: &mut SensorHealth) {
    let steps = ((to - from) / every).round() as u32;
    for k in 0..=steps {
        let t = from + f64::from(k) * every;
        assert_eq!(h.good(sensor, t), None, "no change while it reports at {t}");
        assert!(h.check(t).is_empty(), "nothing lost at {t}");
    }
}

#[test]
fn a_sensor_that_never_reported_is_absent_not_lost() {
    let mut h = SensorHealth::new(HealthConfig::default());
    assert!(h.check(100.0).is_empty());
    assert!(!h.has_reported(Sensor::Camera));
    assert!(h.lost().is_empty());
}

#[test]
fn silence_past_the_timeout_is_a_loss_and_data_again_a_recovery() {
    let mut h = SensorHealth::new(HealthConfig::default());
    fed(Sensor::Lidar, 0.0, 10.0, 0.2, &mut h);
    // 1.0 s timeout (3 x 0.2 s is less): still fine at 10.9 s, lost at 11.1 s.
    assert!(h.check(10.9).is_empty());
    let lost = h.check(11.1);
    assert_eq!(lost.len(), 1);
    assert!(
        matches!(lost[0], Change::Lost { sensor: Sensor::Lidar, silent_for } if (silent_for - 1.1).abs() < 1e-9)
    );
    assert!(h.check(12.0).is_empty(), "lost once, said once");
    assert_eq!(h.lost(), [Sensor::Lidar]);
    assert_eq!(h.lost_since(Sensor::Lidar), Some(11.1));
    let back = h.good(Sensor::Lidar, 30.0);
    assert!(
        matches!(back, Some(Change::Recovered { sensor: Sensor::Lidar, after }) if (after - 20.0).abs() < 1e-9)
    );
    assert!(!h.is_lost(Sensor::Lidar));
    let o = &h.outages()[0];
    assert_eq!(
        (o.lost_at, o.last_good, o.recovered_at),
        (11.1, 10.0, Some(30.0))
    );
}

#[test]
fn a_slow_sensor_gets_a_longer_timeout() {
    // A camera at 0.5 Hz, its gaps within the configured timeout: once its usual
    // interval is learnt, the timeout is three of them.
    let mut h = SensorHealth::new(HealthConfig {
        camera_timeout: 2.5,
        ..HealthConfig::default()
    });
    fed(Sensor::Camera, 0.0, 20.0, 2.0, &mut h);
    assert!((h.timeout(Sensor::Camera) - 6.0).abs() < 0.01);
    assert!(h.check(25.0).is_empty());
    assert_eq!(h.check(26.5).len(), 1);
}

#[test]
fn each_sensor_is_judged_alone() {
    let mut h = SensorHealth::new(HealthConfig::default());
    for k in 0..=50 {
        let t = k as f64 * 0.1;
        h.good(Sensor::Odometry, t);
        if t <= 2.0 {
            h.good(Sensor::Camera, t);
        }
        h.check(t);
    }
    assert_eq!(h.lost(), [Sensor::Camera]);
    assert_eq!(h.outages().len(), 1);
}

#[test]
fn after_a_restart_only_fresh_silence_counts() {
    let mut h = SensorHealth::new(HealthConfig::default());
    fed(Sensor::Odometry, 0.0, 1.0, 0.1, &mut h);
    h.restart();
    assert!(
        h.check(50.0).is_empty(),
        "the link was down, not the wheels"
    );
    h.good(Sensor::Odometry, 50.0);
    assert_eq!(h.check(50.6).len(), 1);
}

#[test]
fn outages_are_bounded() {
    let mut h = SensorHealth::new(HealthConfig::default());
    for k in 0..(OUTAGES_KEPT + 20) {
        let t = k as f64 * 10.0;
        h.good(Sensor::Arm, t);
        h.check(t + 5.0);
    }
    assert_eq!(h.outages().len(), OUTAGES_KEPT);
}
