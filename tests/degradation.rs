//! Graceful degradation (seed 000 §7.2.1) as a user meets it on the twin: a sensor goes
//! quiet, the log and the status panel say so, the robot does what losing that sensor
//! asks, and it carries on once the sensor is back.

use crate::common;

use common::{command, default_app, logged, render, run_to};
use navdeck::app::{App, KeyKind};
use navdeck::geometry::Pose2;
use navdeck::health::Sensor;
use navdeck::keymap::Key;
use navdeck::pilot::behaviours::Behaviour;

fn truth(app: &App) -> Pose2 {
    app.true_pose().expect("the twin knows")
}

/// How far apart two poses are: metres plus radians.
fn apart(a: Pose2, b: Pose2) -> f64 {
    let turn = (a.theta - b.theta).sin().abs();
    a.position().distance(b.position()) + turn
}

/// The mission on the default twin, run to session time `t`.
fn mission_to(t: f64) -> App {
    let mut app = default_app();
    app.handle_key(Key::char('e'), KeyKind::Press, 0.0);
    run_to(&mut app, t);
    app
}

/// Runs on to `until`, asserting at every control period that the robot stands still
/// where it stood at the start and that `holder` has control.
fn stands_still_until(app: &mut App, until: f64, holder: Behaviour) {
    let held = truth(app);
    let mut t = app.now();
    while t < until - 1e-9 {
        t = (t + 0.1).min(until);
        app.update(t);
        let moved = apart(held, truth(app));
        assert!(moved < 1e-6, "moved {moved:.4} by {t:.1} s");
        let winner = app.pilot().arbiter().winner().map(|w| w.0);
        assert_eq!(winner, Some(holder), "at {t:.1} s");
    }
}

/// When `sensor`'s newest outage ended, session seconds.
fn recovered_at(app: &App, sensor: Sensor) -> f64 {
    let outages = app.pilot().sensor_health().outages();
    let last = outages.iter().rev().find(|o| o.sensor == sensor);
    last.and_then(|o| o.recovered_at).expect("recovered")
}

#[test]
fn losing_odometry_stops_the_mission_until_the_wheels_report_again() {
    let mut app = mission_to(40.0);
    command(&mut app, "fault odom+8");
    run_to(&mut app, 41.0);
    assert!(logged(&app, "odometry lost (no wheel travel for"));
    assert!(render(&app).contains("odometry LOST"), "{}", render(&app));
    stands_still_until(&mut app, 47.9, Behaviour::SensorHealth);
    let held = truth(&app);
    run_to(&mut app, 55.0);
    assert!(logged(&app, "odometry back after"));
    assert!(recovered_at(&app, Sensor::Odometry) - 48.0 < 0.5);
    assert!(apart(held, truth(&app)) > 0.05, "the mission drives on");
    assert_eq!(app.link().ground_truth().unwrap().collisions(), 0);
}

#[test]
fn a_dark_camera_holds_the_mission_and_it_resumes_within_5_s_of_light() {
    let mut app = mission_to(40.0);
    command(&mut app, "fault camera+6");
    run_to(&mut app, 41.5);
    assert!(logged(&app, "camera lost (no usable camera frame for"));
    assert!(logged(&app, "holding position, mapping goes on"));
    let screen = render(&app);
    assert!(screen.contains("camera LOST"), "{screen}");
    stands_still_until(&mut app, 45.9, Behaviour::SensorHealth);
    let held = truth(&app);
    run_to(&mut app, 55.0);
    // Seed 000 §6.4.2: "Camera temporary blockage: Recovery within 5 seconds".
    assert!(recovered_at(&app, Sensor::Camera) - 46.0 < 5.0);
    assert!(logged(&app, "camera back after"));
    assert!(apart(held, truth(&app)) > 0.05, "the mission drives on");
    assert!(!render(&app).contains("camera LOST"));
}

#[test]
fn without_the_lidar_keys_drive_slowly_and_the_map_still_stops_the_robot_at_a_wall() {
    let mut app = default_app();
    run_to(&mut app, 1.5);
    command(&mut app, "fault lidar+60");
    // Turn right to face the south wall, then hold `w` towards it.
    let (mut t, mut fastest) = (app.now(), 0.0_f64);
    for (c, seconds) in [('d', 2.0), ('w', 14.0)] {
        let end = t + seconds;
        while t < end {
            app.handle_key(Key::char(c), KeyKind::Press, t);
            t += 1.0 / 30.0;
            app.update(t);
            if app.pilot().sensor_health().is_lost(Sensor::Lidar) {
                let speed = app.link().ground_truth().unwrap().velocity().linear;
                fastest = fastest.max(speed.abs());
            }
        }
    }
    assert!(logged(&app, "lidar lost (no scan for"));
    assert!(logged(&app, "slow safety mode (0.10 m/s"));
    let slow = app.pilot().settings().safety.health.slow_linear;
    assert!(fastest > 0.5 * slow && fastest <= slow + 1e-9, "{fastest}");
    assert_eq!(app.link().ground_truth().unwrap().collisions(), 0);
    assert!(logged(
        &app,
        "behaviour: collision monitor (was sensor health)"
    ));
}

/// A robot turning fast when its odometry goes quiet is stopped, and turns on while it
/// brakes: that turn is reckoned from the command and the base's acceleration limit, so
/// the heading the robot believes is the one it has (without it, 8° off here).
#[test]
fn the_turn_braked_through_after_odometry_is_lost_is_in_the_estimate() {
    let mut app = default_app();
    run_to(&mut app, 1.0);
    let mut t = app.now();
    let mut fault_at = None;
    while t < 3.0 {
        app.handle_key(Key::char('d'), KeyKind::Press, t);
        t += 1.0 / 30.0;
        app.update(t);
        if fault_at.is_none() && t > 2.0 {
            command(&mut app, "fault odom+10");
            fault_at = Some(t);
        }
    }
    assert!(logged(&app, "odometry lost (no wheel travel for"));
    let turning = app.link().ground_truth().unwrap().velocity().angular.abs();
    assert!(turning < 1e-9, "stopped, turning at {turning} rad/s");
    let believed = app.pilot().pose().theta;
    let off = (believed - truth(&app).theta)
        .sin()
        .asin()
        .abs()
        .to_degrees();
    assert!(off < 2.0, "heading {off:.1}° off after the blind turn");
}

#[test]
fn the_health_behaviour_can_be_switched_off_like_any_safety_behaviour() {
    let mut app = mission_to(40.0);
    command(&mut app, "behaviour sensor_health off");
    command(&mut app, "fault odom+3");
    run_to(&mut app, 42.0);
    assert!(logged(&app, "odometry lost"));
    let winner = app.pilot().arbiter().winner().map(|w| w.0);
    assert_ne!(winner, Some(Behaviour::SensorHealth));
}

/// Seed 000 §7.2.1, "arm_control: skip_manipulation_tasks": with the arm silent for good,
/// the mission picks nothing up, explores everything it can and then waits for the arm,
/// standing still, rather than claiming an end; the JSON names the outage.
#[test]
fn with_the_arm_lost_the_mission_explores_on_and_waits_for_it() {
    let dir = common::scratch("arm-lost");
    let config = dir.join("arm.toml");
    std::fs::write(&config, "[arm]\n").unwrap();
    let config = config.to_str().unwrap();
    let args = [
        "mission",
        "--config",
        config,
        "--seed",
        "2",
        "--fault",
        "arm@5",
        "--time-limit",
        "400",
        "--json",
        "--log",
    ];
    let out = common::navdeck(&args);
    let r: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(r["true_delivered"], 0, "{}", r["warnings"]);
    assert_eq!(r["collisions"], 0, "{}", r["warnings"]);
    assert_eq!(r["cause"], "time limit", "{}", r["warnings"]);
    let log = r["log"].to_string();
    assert!(log.contains("arm lost (no joint states for"), "{log}");
    assert!(!log.contains("Picked up"), "{log}");
    assert!(
        log.contains("the arm does not answer - waiting for it"),
        "{log}"
    );
    assert_eq!(r["degraded"][0]["sensor"], "arm");
    assert_eq!(r["degraded"][0]["recovered_s"], serde_json::Value::Null);
}

/// A robot that drives as commanded, speeding up and braking at the default base's
/// 1 m/s², and whose wheels go silent from `silent.0` to `silent.1`; the first travel after it spans the silence (wheels that counted on while
/// their reports were lost) or starts at its end (counts lost with the reports).
struct SilentWheels {
    silent: (f64, f64),
    spans: bool,
    driven: f64,
    speed: f64,
    commanded: f64,
    at: f64,
    reported: f64,
    reported_at: f64,
}

impl navdeck::pilot::Robot for SilentWheels {
    fn poll(&mut self, t: f64) -> Result<navdeck::data::SensorFrame, String> {
        // Linear speed changes at the acceleration limit: the mean speed gives the travel.
        let h = t - self.at;
        let speed = self.speed + (self.commanded - self.speed).clamp(-h, h);
        self.driven += 0.5 * (self.speed + speed) * h;
        (self.speed, self.at) = (speed, t);
        let mut frame = navdeck::data::SensorFrame {
            stamp: t,
            ..Default::default()
        };
        if t >= self.silent.0 && t < self.silent.1 {
            return Ok(frame);
        }
        if !self.spans && self.reported_at < self.silent.1 && t >= self.silent.1 {
            // The counts of the silence are gone: the travel starts at its end.
            self.reported = self.driven;
            self.reported_at = self.silent.1;
        }
        let d = self.driven - self.reported;
        frame.wheels = Some(navdeck::data::WheelTravel { left: d, right: d });
        frame.elapsed = t - self.reported_at;
        (self.reported, self.reported_at) = (self.driven, t);
        Ok(frame)
    }
    fn truth(&self) -> Option<Pose2> {
        None
    }
    fn send(&mut self, command: &navdeck::data::Command) -> Result<(), String> {
        self.commanded = command.twist.linear;
        Ok(())
    }
}

/// Odometry lost mid-drive: the robot stops, what it drove blind is reckoned from the
/// commands, and the estimate neither falls behind (counts lost with the reports) nor
/// runs ahead (a later travel that spans the silence counts it again).
#[test]
fn what_the_robot_drove_blind_is_reckoned_once() {
    use navdeck::pilot::teleop::DriveKey;
    use navdeck::pilot::{Due, Input, Intent, Pilot};
    for spans in [false, true] {
        let settings = navdeck::config::Config::default().pilot_settings();
        let mut pilot = Pilot::new(settings, Pose2::default(), (4.0, 4.0), 0.0);
        let mut robot = SilentWheels {
            silent: (2.0, 4.0),
            spans,
            driven: 0.0,
            speed: 0.0,
            commanded: 0.0,
            at: 0.0,
            reported: 0.0,
            reported_at: 0.0,
        };
        let mut log = Vec::new();
        for k in 1..=60 {
            let t = f64::from(k) * 0.1;
            let forward = Intent::KeyDown {
                key: DriveKey::Forward,
                repeat: k > 1,
            };
            pilot.step(Input::apply(t, forward), &mut robot);
            log.extend(pilot.step(Input::due(t, Due::Tick), &mut robot).log);
        }
        let said = |what: &str| log.iter().any(|l| l.text.contains(what));
        assert!(
            said("m driven meanwhile, reckoned from the commands"),
            "{log:?}"
        );
        assert!(said("odometry back after"), "{log:?}");
        let blind = robot.driven - pilot.odometry_distance();
        assert!(
            blind.abs() < 0.01,
            "spans {spans}: estimate off by {blind:.3} m"
        );
        assert!(
            robot.driven > 0.4,
            "it drove on after the silence: {}",
            robot.driven
        );
    }
}
