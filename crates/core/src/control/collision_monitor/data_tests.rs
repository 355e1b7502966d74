//! The monitor when its data is missing, old, or comes from a map instead of a lidar,
//! and when the command itself is bad.

use super::tests::{BURGER, fresh, points_ahead};
use super::*;
use crate::geometry::{Point2, Pose2, Twist};
use std::f64::consts::PI;

#[test]
fn data_too_old_or_never_seen_blocks_motion_until_it_comes() {
    let monitor = CollisionMonitor::new(&SafetyConfig::default(), BURGER);
    let nothing_near = points_ahead(2.0);
    let drive = Twist::new(0.2, 0.5);
    let stale = Obstacles {
        age: Some(0.61),
        ..fresh(&nothing_near)
    };
    let verdict = monitor.check(drive, &stale);
    assert_eq!((verdict.command, verdict.blocked), (Twist::ZERO, true));
    assert_eq!(
        verdict.reason.as_deref(),
        Some("collision monitor: no scan for 0.6 s: motion blocked")
    );
    let never = monitor.check(drive, &Obstacles { age: None, ..stale });
    assert_eq!(
        never.reason.as_deref(),
        Some("collision monitor: no scan yet: motion blocked")
    );
    let nan = monitor.check(
        drive,
        &Obstacles {
            age: Some(f64::NAN),
            ..stale
        },
    );
    assert_eq!(nan.command, Twist::ZERO);
    // Standing still is not worth a line.
    assert_eq!(monitor.check(Twist::ZERO, &stale).reason, None);
    // In time: through.
    let ok = Obstacles {
        age: Some(0.49),
        ..stale
    };
    assert_eq!(monitor.check(drive, &ok).command, drive);
}

#[test]
fn without_block_if_invalid_old_data_lets_the_command_through_unchecked() {
    let config = SafetyConfig {
        block_if_invalid: false,
        ..SafetyConfig::default()
    };
    let monitor = CollisionMonitor::new(&config, BURGER);
    let wall = points_ahead(0.12);
    let stale = Obstacles {
        age: Some(1.0),
        ..fresh(&wall)
    };
    let verdict = monitor.check(Twist::new(0.2, 0.0), &stale);
    assert_eq!(
        (verdict.command, verdict.blocked),
        (Twist::new(0.2, 0.0), false)
    );
    assert_eq!(
        verdict.reason.as_deref(),
        Some("collision monitor: no scan for 1.0 s: not checked")
    );
}

#[test]
fn a_robot_without_a_lidar_stops_at_the_walls_of_its_map() {
    use crate::map::grid::{FREE, OCCUPIED, OccupancyGrid};
    // A 2 m map of 5 cm cells with a wall along x = 1.00..1.05.
    let mut grid = OccupancyGrid::new(40, 40, 0.05, Point2::new(0.0, 0.0), FREE);
    for cy in 0..40 {
        grid.set(20, cy, OCCUPIED);
    }
    let monitor = CollisionMonitor::new(&SafetyConfig::default(), BURGER);
    let drive = Twist::new(0.2, 0.0);
    let near = points_from_grid(&grid, Pose2::new(0.87, 1.0, 0.0), 1.0);
    let map = |points| Obstacles {
        points,
        age: Some(0.1),
        source: SourceKind::Map,
    };
    let verdict = monitor.check(drive, &map(&near));
    assert_eq!(verdict.command, Twist::ZERO);
    assert!((verdict.nearest_ahead.unwrap() - 0.13).abs() < 1e-9);
    // Facing away from the wall, the same place lets it drive.
    let facing_away = points_from_grid(&grid, Pose2::new(0.87, 1.0, PI), 1.0);
    assert_eq!(monitor.check(drive, &map(&facing_away)).command, drive);
    let lost = Obstacles {
        age: None,
        ..map(&near)
    };
    assert_eq!(
        monitor.check(drive, &lost).reason.as_deref(),
        Some("collision monitor: no pose on the map yet: motion blocked")
    );
}

#[test]
fn a_command_that_is_not_a_number_is_never_sent() {
    let monitor = CollisionMonitor::new(&SafetyConfig::default(), BURGER);
    let verdict = monitor.check(Twist::new(f64::NAN, 0.0), &fresh(&points_ahead(2.0)));
    assert_eq!(verdict.command, Twist::ZERO);
}
