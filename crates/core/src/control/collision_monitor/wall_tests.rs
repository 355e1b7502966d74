//! Holding `w` towards a wall: a robot driven straight at it at a TurtleBot3's top speed,
//! the monitor applied every 0.1 s tick to a fresh scan, the command integrated.

use super::tests::{BURGER, wall_scan};
use super::*;
use crate::geometry::{Pose2, Twist};

/// TurtleBot3 Burger's top speed, m/s (seed 004: `v_max = 0.22 m/s`).
const TOP_SPEED: f64 = 0.22;
/// The control period, s (seed 001 `delta_t`).
const TICK: f64 = 0.1;
/// The default stop zone's radius.
const STOP_RADIUS: f64 = 0.15;

/// What a drive at a wall came to.
#[derive(Debug)]
struct Drive {
    /// The least distance from the robot's centre to the wall, m.
    closest: f64,
    /// Where it ended, m from the wall.
    last: f64,
    /// The last verdict.
    verdict: Verdict,
}

/// The nearest a TurtleBot3's LDS-01 reads, m: a wall closer than this is not in its scan.
const LDS_RANGE_MIN: f64 = 0.12;

/// Asks for `asked` every tick for `ticks` ticks, starting `start` metres from a wall
/// ahead, with a scan (out to 3.5 m) each tick.
fn drive(monitor: &CollisionMonitor, start: f64, asked: Twist, ticks: usize) -> Drive {
    drive_seeing_from(LDS_RANGE_MIN, monitor, start, asked, ticks)
}

/// `drive` with a lidar that reads from `range_min` out.
fn drive_seeing_from(
    range_min: f64,
    monitor: &CollisionMonitor,
    start: f64,
    asked: Twist,
    ticks: usize,
) -> Drive {
    let mut distance = start;
    let mut closest = start;
    let mut verdict = None;
    for _ in 0..ticks {
        let scan = wall_scan(Some(distance), None, range_min);
        let points = points_from_scan(&scan, Pose2::default());
        let obstacles = Obstacles {
            points: &points,
            age: Some(0.05),
            source: SourceKind::Scan,
        };
        let v = monitor.check(asked, &obstacles);
        // Straight-line kinematics over one tick.
        distance -= v.command.linear * TICK;
        closest = closest.min(distance);
        verdict = Some(v);
    }
    Drive {
        closest,
        last: distance,
        verdict: verdict.expect("at least one tick"),
    }
}

#[test]
fn a_robot_driven_at_a_wall_with_only_a_stop_zone_halts_at_the_zone_edge() {
    let config = SafetyConfig {
        polygons: vec![PolygonConfig::new("stop", ActionType::Stop).circle(STOP_RADIUS)],
        ..SafetyConfig::default()
    };
    let monitor = CollisionMonitor::new(&config, BURGER);
    let run = drive(&monitor, 1.0, Twist::new(TOP_SPEED, 0.0), 100);
    assert!(run.closest > BURGER, "{run:?}");
    // Within one tick's travel (2.2 cm) inside the zone's edge, and held there.
    assert!(
        run.last < STOP_RADIUS && run.last > STOP_RADIUS - TOP_SPEED * TICK,
        "{run:?}"
    );
    assert_eq!(run.verdict.command, Twist::ZERO);
    // Pressing `s` backs it away.
    let back = drive(&monitor, run.last, Twist::new(-TOP_SPEED, 0.0), 10);
    assert!(
        (back.last - run.last - 10.0 * TOP_SPEED * TICK).abs() < 1e-9,
        "{back:?}"
    );
}

#[test]
fn a_robot_driven_at_a_wall_with_the_default_zones_slows_and_halts_at_the_stop_zone() {
    let monitor = CollisionMonitor::new(&SafetyConfig::default(), BURGER);
    let run = drive(&monitor, 2.0, Twist::new(TOP_SPEED, 0.0), 600);
    assert!(run.closest > BURGER, "{run:?}");
    // The approach zone has slowed it to a crawl by then: it stops within millimetres.
    assert!(
        run.last < STOP_RADIUS && run.last > STOP_RADIUS - 0.01,
        "{run:?}"
    );
    assert_eq!(run.verdict.command, Twist::ZERO);
    let reason = run.verdict.reason.clone().unwrap();
    assert!(
        reason.starts_with("collision monitor: stopping, obstacle 0.1"),
        "{reason}"
    );
    assert!(reason.ends_with("in `stop`"), "{reason}");
    // And backs away at once.
    let back = drive(&monitor, run.last, Twist::new(-TOP_SPEED, 0.0), 1);
    assert_eq!(back.verdict.command, Twist::new(-TOP_SPEED, 0.0));
}

#[test]
fn a_robot_with_only_an_approach_zone_never_touches_the_wall() {
    let config = SafetyConfig {
        polygons: vec![PolygonConfig {
            simulation_time_step: 0.02,
            ..PolygonConfig::new("approach", ActionType::Approach)
        }],
        ..SafetyConfig::default()
    };
    let monitor = CollisionMonitor::new(&config, BURGER);
    // A lidar that reads from 5 cm: the LDS-01's 0.12 m lies beyond the Burger's
    // footprint, and a wall inside that leaves the scan (a stop zone wider than 0.12 m
    // keeps the robot out of that blind ring).
    let run = drive_seeing_from(0.05, &monitor, 1.0, Twist::new(TOP_SPEED, 0.0), 600);
    assert!(run.closest > BURGER, "{run:?}");
    // It creeps up to a step's travel at the asked speed (4.4 mm) from contact, and stops.
    assert!(run.last - BURGER < 0.01, "{run:?}");
    assert_eq!(run.verdict.command, Twist::ZERO);
}
