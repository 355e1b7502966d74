//! Faults injected into the twin (`--fault`), as the pilot's side of the link sees them:
//! frames without scans, wheel travel or arm joints exactly while a fault lasts, dark
//! camera frames, and slip the odometry does not see, while the truth tells what happened.

use navdeck::arm::ArmConfig;
use navdeck::config::Config;
use navdeck::data::{ArmTarget, SensorFrame};
use navdeck::geometry::Twist;
use navdeck::link::RobotLink;
use navdeck::link::sim::SimLink;
use navdeck::sim::{FaultKind, Twin, World};

/// Seed 001's robot and sensors with the encoders' own noise and slip turned off.
fn quiet() -> Config {
    let mut c = Config::default();
    c.sim.encoders.noise_std = 0.0;
    c.sim.encoders.slip_probability = 0.0;
    c
}

/// A twin in the built-in arena with `faults` scheduled.
fn twin_with(config: &Config, faults: &[&str]) -> Twin {
    let mut twin = Twin::new(World::default_arena(), &config.robot, &config.sim, 1);
    for f in faults {
        twin.faults_mut().schedule(f.parse().unwrap());
    }
    twin
}

/// The frames of `seconds` at `twist`, taken every 0.1 s as the pilot polls.
fn frames(twin: &mut Twin, twist: Twist, seconds: f64) -> Vec<SensorFrame> {
    twin.set_command(twist);
    let n = (seconds / 0.1).round() as usize;
    (0..n)
        .map(|_| {
            twin.step(0.1);
            twin.take_frame()
        })
        .collect()
}

/// Whether frame time `t` lies in [from, to).
fn within(t: f64, from: f64, to: f64) -> bool {
    t >= from - 1e-9 && t < to - 1e-9
}

const SPIN: Twist = Twist {
    linear: 0.0,
    angular: 0.5,
};

#[test]
fn a_lidar_fault_takes_the_scans_away_exactly_while_it_lasts() {
    let config = quiet();
    let with = frames(&mut twin_with(&config, &["lidar@1+1"]), SPIN, 3.0);
    let without = frames(&mut twin_with(&config, &[]), SPIN, 3.0);
    for (a, b) in with.iter().zip(&without) {
        if within(a.stamp, 1.0, 2.0) {
            assert!(a.scan.is_none(), "a scan at {} s", a.stamp);
        } else {
            // Before and after, scans come as they do without the fault.
            assert_eq!(a.scan.is_some(), b.scan.is_some(), "at {} s", a.stamp);
        }
    }
    let scanned = |from, to| {
        (with.iter())
            .filter(|f| within(f.stamp, from, to))
            .any(|f| f.scan.is_some())
    };
    assert!(scanned(0.0, 1.0) && scanned(2.0, 3.0));
    // Frames keep coming all the while, with the rest of what the robot reports.
    assert!(with.iter().all(|f| f.wheels.is_some()));
}

#[test]
fn an_odometry_fault_leaves_frames_without_wheel_travel_and_its_motion_unreported() {
    let config = quiet();
    let mut twin = twin_with(&config, &["odom@1+1"]);
    let with = frames(&mut twin, SPIN, 3.0);
    let mut plain = twin_with(&config, &[]);
    let without = frames(&mut plain, SPIN, 3.0);
    for f in &with {
        let silent = within(f.stamp, 1.0, 2.0);
        assert_eq!(f.wheels.is_none(), silent, "at {} s", f.stamp);
        if silent {
            assert_eq!(f.elapsed, 0.0);
        }
    }
    let turned = |frames: &[SensorFrame]| -> f64 {
        frames
            .iter()
            .filter_map(|f| f.wheels)
            .map(|w| w.right)
            .sum()
    };
    // A third of the time at full speed went unreported: the odometry is behind by it.
    let (reported, full) = (turned(&with), turned(&without));
    let lost = 0.5 * config.robot.track / 2.0;
    assert!(
        (full - reported - lost).abs() < 0.01,
        "reported {reported} m of {full} m"
    );
    // The truth turned all the while.
    assert!((twin.pose().theta - plain.pose().theta).abs() < 1e-9);
    // After the fault the travel again covers the time it says it does.
    let after: Vec<&SensorFrame> = with.iter().filter(|f| f.stamp > 2.05).collect();
    for f in after {
        let w = f.wheels.unwrap();
        let speed = w.right / f.elapsed;
        assert!((speed - lost).abs() < 0.01, "{speed} m/s at {} s", f.stamp);
    }
}

#[test]
fn slipping_wheels_move_the_robot_less_than_the_odometry_says() {
    let config = quiet();
    let mut twin = twin_with(&config, &["slip@0+2:0.5"]);
    let ahead = Twist::new(0.1, 0.0);
    let slipping = frames(&mut twin, ahead, 2.0);
    let odometry = |frames: &[SensorFrame]| -> f64 {
        (frames.iter())
            .filter_map(|f| f.wheels)
            .map(|w| (w.left + w.right) / 2.0)
            .sum()
    };
    let (said, truly) = (odometry(&slipping), twin.distance_driven());
    assert!(said > 0.15, "{said}");
    assert!((truly - said / 2.0).abs() < 0.002, "{truly} m of {said} m");
    // Once it stops slipping, the wheels deliver what they are asked again.
    let gripping = frames(&mut twin, ahead, 2.0);
    let further = twin.distance_driven() - truly;
    assert!((further - odometry(&gripping)).abs() < 0.002);
}

#[test]
fn a_dark_camera_still_sends_frames_but_sees_nothing_in_them() {
    let mut config = quiet();
    config.sim.camera.miss_probability = 0.0;
    let with = frames(&mut twin_with(&config, &["camera@1+2"]), SPIN, 4.0);
    let without = frames(&mut twin_with(&config, &[]), SPIN, 4.0);
    let mut seen_in_window = 0;
    for (a, b) in with.iter().zip(&without) {
        assert_eq!(a.sightings.is_some(), b.sightings.is_some());
        if within(a.stamp, 1.0, 3.0) {
            assert_eq!(a.sightings.as_deref(), Some(&[][..]), "at {} s", a.stamp);
            seen_in_window += b.sightings.as_ref().map_or(0, Vec::len);
        } else {
            // The same markers as without the fault (their noise drawn afresh after it).
            let ids = |f: &SensorFrame| -> Option<Vec<u32>> {
                (f.sightings.as_ref()).map(|s| s.iter().map(|m| m.id).collect())
            };
            assert_eq!(ids(a), ids(b), "at {} s", a.stamp);
        }
    }
    assert!(seen_in_window > 0, "markers were in view while it was dark");
}

#[test]
fn an_arm_fault_silences_the_joints_and_drops_the_arms_commands() {
    let config = quiet();
    let mut twin = twin_with(&config, &["arm@0+1"]);
    twin.add_arm(&ArmConfig::default());
    let home = twin.arm_joints().unwrap();
    let target = ArmTarget {
        joints: [0.5, home[1], home[2], home[3]],
        within: 1.0,
    };
    twin.command_arm(&target);
    let during = frames(&mut twin, Twist::ZERO, 0.9);
    assert!(during.iter().all(|f| f.arm.is_none()));
    assert_eq!(
        twin.arm_joints(),
        Some(home),
        "a command while silent is dropped"
    );
    let after = frames(&mut twin, Twist::ZERO, 0.2);
    assert!(after.last().unwrap().arm.is_some());
    twin.command_arm(&target);
    frames(&mut twin, Twist::ZERO, 3.0);
    assert!((twin.arm_joints().unwrap()[0] - 0.5).abs() < 0.01);
}

#[test]
fn the_sim_link_says_when_a_fault_begins_and_ends_and_which_are_in_force() {
    let config = quiet();
    let mut link = SimLink::new(twin_with(&config, &["camera@0.5+0.5"]), 0.0);
    let mut said = Vec::new();
    let mut in_force = Vec::new();
    for k in 1..=12 {
        link.poll(f64::from(k) * 0.1).unwrap();
        said.extend(link.take_notes().into_iter().map(|n| n.text));
        in_force.push(link.faults().unwrap().is_active(FaultKind::Camera));
    }
    assert_eq!(
        said,
        [
            "fault injected: camera dark for 0.5 s",
            "fault cleared: camera"
        ]
    );
    let expected: Vec<bool> = (1..=12).map(|k| (5..10).contains(&k)).collect();
    assert_eq!(in_force, expected);
}

#[cfg(feature = "vision")]
#[test]
fn the_rendered_camera_says_its_frames_are_dark() {
    let config = Config::default();
    let mut twin = twin_with(&config, &["camera@0.5"]);
    let frames = navdeck::sim::CameraFrames::Whole;
    twin.use_rendered_camera(&crate::vision_support::level(), None, frames)
        .unwrap();
    twin.set_command(SPIN);
    twin.step(0.4);
    let lit = twin.take_frame().camera.expect("a camera status");
    assert!(lit.error.is_none(), "{lit:?}");
    twin.step(0.6);
    let frame = twin.take_frame();
    assert_eq!(frame.sightings, Some(Vec::new()));
    let dark = frame.camera.expect("a camera status while dark");
    assert!(dark.error.is_some_and(|e| e.contains("dark")));
}
