//! The monitor as a driver meets it: hand-made scans of a wall, each zone type alone and
//! the default zones together.

use super::*;
use crate::data::LaserScan;
use crate::geometry::{Point2, Pose2, Twist};
use std::f64::consts::PI;

/// A TurtleBot3 Burger's footprint radius, metres.
pub(super) const BURGER: f64 = 0.105;

/// A 360-beam scan (one beam a degree, from -pi) of flat walls square to the robot,
/// `ahead` and `behind` metres from its centre, as a lidar with `range_min` reads them.
pub(super) fn wall_scan(ahead: Option<f64>, behind: Option<f64>, range_min: f64) -> LaserScan {
    let increment = 2.0 * PI / 360.0;
    let ranges = (0..360)
        .map(|k| {
            let a = -PI + k as f64 * increment;
            let wall = if a.cos() > 0.0 { ahead } else { behind };
            match wall {
                Some(d) if a.cos().abs() > 1e-9 => (d / a.cos().abs()) as f32,
                _ => f32::INFINITY,
            }
        })
        .map(|r| if r > 3.5 { f32::INFINITY } else { r })
        .collect();
    LaserScan {
        angle_min: -PI,
        angle_increment: increment,
        range_min,
        range_max: 3.5,
        ranges,
    }
}

pub(super) fn points_ahead(d: f64) -> Vec<Point2> {
    points_from_scan(&wall_scan(Some(d), None, 0.05), Pose2::default())
}

pub(super) fn fresh(points: &[Point2]) -> Obstacles<'_> {
    Obstacles {
        points,
        age: Some(0.05),
        source: SourceKind::Scan,
    }
}

/// A monitor with only `zone`.
fn only(zone: PolygonConfig) -> CollisionMonitor {
    let config = SafetyConfig {
        polygons: vec![zone],
        ..SafetyConfig::default()
    };
    CollisionMonitor::new(&config, BURGER)
}

fn acted(verdict: &Verdict) -> Option<(&str, ActionType)> {
    verdict
        .acted
        .as_ref()
        .map(|a| (a.polygon.as_str(), a.action))
}

#[test]
fn a_stop_zone_stops_the_drive_at_a_wall_and_lets_the_robot_back_away_and_turn() {
    let monitor = only(PolygonConfig::new("stop", ActionType::Stop).circle(0.15));
    let wall = points_ahead(0.14);
    let forward = monitor.check(Twist::new(0.2, 0.0), &fresh(&wall));
    assert_eq!(forward.command, Twist::ZERO);
    assert_eq!(acted(&forward), Some(("stop", ActionType::Stop)));
    assert_eq!(
        forward.reason.as_deref(),
        Some("collision monitor: stopping, obstacle 0.14 m ahead in `stop`")
    );
    let back = monitor.check(Twist::new(-0.2, 0.0), &fresh(&wall));
    assert_eq!((back.command, back.reason), (Twist::new(-0.2, 0.0), None));
    let turn = monitor.check(Twist::new(0.0, 2.0), &fresh(&wall));
    assert_eq!(turn.command, Twist::new(0.0, 2.0));
    // Forward and left: the turn goes on, the drive into the wall does not.
    let arc = monitor.check(Twist::new(0.2, 1.0), &fresh(&wall));
    assert_eq!(arc.command, Twist::new(0.0, 1.0));
}

#[test]
fn a_wall_behind_in_the_stop_zone_blocks_reversing_not_driving_off() {
    let monitor = only(PolygonConfig::new("stop", ActionType::Stop).circle(0.15));
    let wall = points_from_scan(&wall_scan(None, Some(0.13), 0.05), Pose2::default());
    let reverse = monitor.check(Twist::new(-0.1, 0.0), &fresh(&wall));
    assert_eq!(reverse.command, Twist::ZERO);
    assert_eq!(
        reverse.reason.as_deref(),
        Some("collision monitor: stopping, obstacle 0.13 m behind in `stop`")
    );
    let off = monitor.check(Twist::new(0.1, 0.0), &fresh(&wall));
    assert_eq!(off.command, Twist::new(0.1, 0.0));
}

#[test]
fn a_wall_beyond_the_stop_zone_lets_the_robot_drive_on() {
    let monitor = only(PolygonConfig::new("stop", ActionType::Stop).circle(0.15));
    let verdict = monitor.check(Twist::new(0.2, 0.0), &fresh(&points_ahead(0.16)));
    assert_eq!(verdict.command, Twist::new(0.2, 0.0));
    assert_eq!(verdict.acted, None);
    assert!((verdict.nearest_ahead.unwrap() - 0.16).abs() < 1e-6);
}

#[test]
fn a_slowdown_zone_halves_the_drive_towards_a_wall_ahead_but_not_away() {
    let zone = PolygonConfig::new("slowdown", ActionType::Slowdown).polygon(&[
        [0.5, 0.15],
        [0.5, -0.15],
        [0.0, -0.15],
        [0.0, 0.15],
    ]);
    let monitor = only(zone);
    let wall = points_ahead(0.42);
    let slowed = monitor.check(Twist::new(0.16, 0.4), &fresh(&wall));
    assert_eq!(slowed.command, Twist::new(0.08, 0.2));
    assert_eq!(
        slowed.reason.as_deref(),
        Some("collision monitor: slowing to 0.08 m/s, obstacle 0.42 m ahead in `slowdown`")
    );
    let away = monitor.check(Twist::new(-0.16, 0.0), &fresh(&wall));
    assert_eq!(away.command, Twist::new(-0.16, 0.0));
    // Past the zone's far edge, nothing.
    let far = monitor.check(Twist::new(0.16, 0.0), &fresh(&points_ahead(0.55)));
    assert_eq!(far.command, Twist::new(0.16, 0.0));
}

#[test]
fn a_limit_zone_caps_speed_and_turn_with_obstacles_near_whichever_way() {
    let zone = PolygonConfig {
        linear_limit: 0.1,
        angular_limit: 0.5,
        ..PolygonConfig::new("limit", ActionType::Limit).circle(0.6)
    };
    let monitor = only(zone);
    let wall = points_ahead(0.5);
    let fast = monitor.check(Twist::new(0.22, 2.0), &fresh(&wall));
    assert_eq!(fast.command, Twist::new(0.1, 0.5));
    assert_eq!(acted(&fast), Some(("limit", ActionType::Limit)));
    let reverse = monitor.check(Twist::new(-0.22, 0.0), &fresh(&wall));
    assert_eq!(reverse.command, Twist::new(-0.1, 0.0));
    let open = monitor.check(Twist::new(0.22, 2.0), &fresh(&points_ahead(0.7)));
    assert_eq!(open.command, Twist::new(0.22, 2.0));
}

#[test]
fn an_approach_zone_slows_so_contact_stays_two_seconds_away() {
    let monitor = only(PolygonConfig {
        simulation_time_step: 0.02,
        ..PolygonConfig::new("approach", ActionType::Approach)
    });
    // 0.5 m ahead: 0.395 m from the footprint. The fourth beam (2 degrees off, 1.7 cm
    // aside) enters the footprint after 0.3965 m, 1.802 s at 0.22 m/s: the first step
    // after it is 1.82 s, the last step clear 1.80 s, and 1.80 / 2 keeps 0.9 of the speed.
    let verdict = monitor.check(Twist::new(0.22, 0.0), &fresh(&points_ahead(0.5)));
    assert_eq!(acted(&verdict), Some(("approach", ActionType::Approach)));
    assert!(
        (verdict.command.linear - 0.9 * 0.22).abs() < 1e-9,
        "{verdict:?}"
    );
    assert_eq!(
        verdict.reason.as_deref(),
        Some(
            "collision monitor: slowing to 0.20 m/s (contact in 1.82 s at 0.22 m/s), obstacle 0.50 m ahead in `approach`"
        )
    );
    // At the slowed speed the wall is 2 s from the footprint, give or take a step.
    let contact = (0.5 - BURGER) / verdict.command.linear;
    assert!((contact - 2.0).abs() < 0.02, "{contact}");
    // 1 m ahead is 4 s away: beyond the horizon, nothing to do.
    let far = monitor.check(Twist::new(0.22, 0.0), &fresh(&points_ahead(1.0)));
    assert_eq!(far.acted, None);
}

#[test]
fn an_approach_zone_stops_a_fast_robot_a_step_short_of_contact() {
    let monitor = only(PolygonConfig {
        simulation_time_step: 0.02,
        ..PolygonConfig::new("approach", ActionType::Approach)
    });
    // 3 mm from the footprint: at 0.22 m/s the first 0.02 s step (4.4 mm) touches.
    let verdict = monitor.check(Twist::new(0.22, 0.0), &fresh(&points_ahead(0.108)));
    assert_eq!(verdict.command, Twist::ZERO);
    assert_eq!(
        verdict.reason.as_deref(),
        Some(
            "collision monitor: stopping (contact in 0.02 s at 0.22 m/s), obstacle 0.11 m ahead in `approach`"
        )
    );
    // Backing off predicts no contact.
    let back = monitor.check(Twist::new(-0.22, 0.0), &fresh(&points_ahead(0.108)));
    assert_eq!(back.command, Twist::new(-0.22, 0.0));
}

#[test]
fn fewer_points_than_min_points_do_not_act() {
    let monitor = only(PolygonConfig::new("stop", ActionType::Stop).circle(0.15));
    // Three hits of a thin table leg 0.12 m ahead: below Nav2 Jazzy's default of 4.
    let leg: Vec<Point2> = [-0.004, 0.0, 0.004]
        .iter()
        .map(|&y| Point2::new(0.12, y))
        .collect();
    let three = monitor.check(Twist::new(0.2, 0.0), &fresh(&leg));
    assert_eq!(three.command, Twist::new(0.2, 0.0));
    let mut four = leg.clone();
    four.push(Point2::new(0.121, 0.008));
    let stopped = monitor.check(Twist::new(0.2, 0.0), &fresh(&four));
    assert_eq!(stopped.command, Twist::ZERO);
    // Points behind do not count towards stopping a forward drive.
    let mut mixed = leg;
    mixed.push(Point2::new(-0.12, 0.0));
    assert_eq!(
        monitor.check(Twist::new(0.2, 0.0), &fresh(&mixed)).acted,
        None
    );
}

#[test]
fn the_most_restrictive_zone_wins() {
    // The default zones with the slowdown switched on.
    let mut config = SafetyConfig::default();
    for zone in &mut config.polygons {
        zone.enabled = true;
    }
    let monitor = CollisionMonitor::new(&config, BURGER);
    // 0.14 m: inside stop, slowdown and approach; the stop wins.
    let close = monitor.check(Twist::new(0.22, 0.0), &fresh(&points_ahead(0.14)));
    assert_eq!(acted(&close), Some(("stop", ActionType::Stop)));
    // 0.3 m: slowdown keeps 0.11 m/s, approach less (0.195 m at 0.22 m/s is 0.89 s).
    let near = monitor.check(Twist::new(0.22, 0.0), &fresh(&points_ahead(0.3)));
    assert_eq!(acted(&near), Some(("approach", ActionType::Approach)));
    assert!(
        near.command.linear < 0.11 && near.command.linear > 0.09,
        "{near:?}"
    );
    // 0.45 m: approach keeps 0.19 m/s, the slowdown's half is slower.
    let ahead = monitor.check(Twist::new(0.22, 0.0), &fresh(&points_ahead(0.45)));
    assert_eq!(acted(&ahead), Some(("slowdown", ActionType::Slowdown)));
    assert_eq!(ahead.command, Twist::new(0.11, 0.0));
}
