//! The route driver closed round a plain robot: commands integrated exactly for the
//! truth, and with a wheel odometry that reads 3 % long and turns 4 % short for the
//! estimate; a camera that sees the tags within its view of the floor, exactly.

use super::*;
use crate::geometry::{Pose2, wrap_angle};
use crate::sim::tag_camera::TagCamera;
use crate::tags::TagMap;
use crate::tags::graph::Blocked;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

const PERIOD: f64 = 1.0 / 30.0;

fn warehouse() -> TagMap {
    TagMap::parse(include_str!("../../../../../maps/tag_warehouse.yaml")).unwrap()
}

/// The tags in view from `truth`, exactly.
fn sightings(map: &TagMap, truth: Pose2, look: f64) -> Vec<TagSighting> {
    let camera = TagCamera {
        look,
        half_length: 0.15,
        half_width: 0.2,
        offset_sd: 0.0,
        angle_sd: 0.0,
    };
    camera.sightings(map, truth, &mut ChaCha8Rng::seed_from_u64(0))
}

/// What a run of one route came to.
struct Outcome {
    events: Vec<DriveEvent>,
    truth: Pose2,
    /// Each turn's true heading error at its end, radians.
    turn_errors: Vec<f64>,
    seconds: f64,
}

/// A camera whose frames come every `every` control periods (1 for every period, 2 for a
/// 15 Hz camera under the 30 Hz loop): the periods between see nothing.
fn drive_seeing_every(
    map: &TagMap,
    route: &crate::tags::Route,
    start: Pose2,
    every: usize,
) -> Outcome {
    let setup = DriveSetup {
        gains: DriveGains::from_map(map),
        ..DriveSetup::default()
    };
    let (mut truth, mut odom) = (start, Pose2::new(0.0, 0.0, 0.0));
    let mut driver = TagDriver::new(map, route, setup, start, odom);
    let (mut events, mut turn_errors) = (Vec::new(), Vec::new());
    let (mut t, mut period) = (0.0, 0);
    while t < 1200.0 && !matches!(driver.phase(), Phase::Done | Phase::Failed) {
        let frame = period % every == 0;
        period += 1;
        let seen = if frame {
            sightings(map, truth, setup.look)
        } else {
            Vec::new()
        };
        let target = match driver.phase() {
            Phase::Turn { target, .. } => Some(target),
            _ => None,
        };
        let ((v, w), happened) = driver.step(map, odom, &seen);
        for e in &happened {
            if let (DriveEvent::Turned { .. }, Some(target)) = (e, target) {
                turn_errors.push(wrap_angle(target - truth.theta));
            }
        }
        events.extend(happened);
        // Unicycle motion over one period (exact for constant v, w).
        let step = |p: Pose2, v: f64, w: f64| {
            let mid = p.theta + w * PERIOD / 2.0;
            Pose2::new(
                p.x + v * PERIOD * mid.cos(),
                p.y + v * PERIOD * mid.sin(),
                wrap_angle(p.theta + w * PERIOD),
            )
        };
        truth = step(truth, v, w);
        odom = step(odom, 1.03 * v, 0.96 * w);
        t += PERIOD;
    }
    Outcome {
        events,
        truth,
        turn_errors,
        seconds: t,
    }
}

/// The dock pose: the camera's image centre over the dock tag, facing +x.
fn dock_pose(map: &TagMap, look: f64) -> Pose2 {
    let dock = &map.tags[&map.dock];
    over_point(dock.x, dock.y, 0.0, look)
}

#[test]
fn every_warehouse_task_ends_square_on_the_dock_within_the_seeds_bounds() {
    every_task_ends_on_the_dock(1);
}

#[test]
fn a_camera_at_half_the_control_rate_still_ends_every_task_on_the_dock() {
    // A frame every other period: the periods between must not lose the tag aligned on.
    every_task_ends_on_the_dock(2);
}

fn every_task_ends_on_the_dock(camera_every: usize) {
    let map = warehouse();
    let look = DriveSetup::default().look;
    let mut turns = 0;
    for name in map.tasks.keys() {
        let route = map.task_route(name, &Blocked::new()).unwrap().unwrap();
        let start = dock_pose(&map, look);
        let out = drive_seeing_every(&map, &route, start, camera_every);
        assert!(
            out.events.contains(&DriveEvent::Done),
            "{name}: {:?}",
            out.events.last()
        );
        // seed 003 §3.3: back at the dock within 5 cm to the side and 5° of heading.
        let end = dock_pose(&map, look);
        let side = (out.truth.y - end.y).abs();
        let heading = wrap_angle(out.truth.theta - end.theta).abs().to_degrees();
        assert!(side < 0.05, "{name}: {side:.3} m to the side");
        assert!(heading < 5.0, "{name}: {heading:.2} degrees off");
        let arrivals = out
            .events
            .iter()
            .filter(|e| matches!(e, DriveEvent::Arrived { .. }))
            .count();
        assert_eq!(arrivals, route.legs.len(), "{name}");
        for e in &out.turn_errors {
            assert!(
                e.abs().to_degrees() < 5.0,
                "{name}: a turn ended {:.2} degrees off",
                e.to_degrees()
            );
        }
        turns += out.turn_errors.len();
        assert!(out.seconds < 1200.0);
    }
    assert!(turns >= 10, "{turns} turns in all");
}

#[test]
fn a_tag_missing_from_the_floor_fails_its_leg_by_name_after_searching() {
    let map = warehouse();
    let route = map.task_route("task1", &Blocked::new()).unwrap().unwrap();
    // The camera sees a floor where tag 120 was taken up.
    let mut floor = map.clone();
    floor.tags.remove(&120);
    let setup = DriveSetup::default();
    let start = dock_pose(&map, setup.look);
    let (mut truth, mut odom) = (start, Pose2::new(0.0, 0.0, 0.0));
    let mut driver = TagDriver::new(&map, &route, setup, start, odom);
    let mut failed = None;
    for _ in 0..30 * 600 {
        let seen = sightings(&floor, truth, setup.look);
        let ((v, w), events) = driver.step(&map, odom, &seen);
        for e in events {
            if let DriveEvent::Failed { leg, why } = e {
                failed = Some((leg, why));
            }
        }
        if failed.is_some() {
            break;
        }
        let p = truth;
        truth = Pose2::new(
            p.x + v * PERIOD * p.theta.cos(),
            p.y + v * PERIOD * p.theta.sin(),
            p.theta + w * PERIOD,
        );
        odom = Pose2::new(
            odom.x + v * PERIOD * odom.theta.cos(),
            odom.y + v * PERIOD * odom.theta.sin(),
            odom.theta + w * PERIOD,
        );
    }
    let (leg, why) = failed.expect("the leg to tag 120 fails");
    assert_eq!(route.legs[leg].to, 120);
    assert!(why.contains("tag 120 not seen"), "{why}");
}
