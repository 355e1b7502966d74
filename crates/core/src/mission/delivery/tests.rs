//! The delivery's choice of drop place as the gate and the map change.

use super::*;
use crate::geometry::Point2;
use crate::mission::drop_places::DROP_PLACES;

fn gate(normal: (f64, f64)) -> Gate {
    Gate {
        colour: Colour::Red,
        markers: [401, 402],
        center: Point2::new(0.0, 2.0),
        normal,
    }
}

fn goal(d: &Delivery) -> Point2 {
    match &d.stage {
        Stage::Travel(leg) => leg.goal,
        _ => panic!("not travelling"),
    }
}

#[test]
fn a_gate_that_turns_on_the_way_gets_a_new_drop_place_and_a_steady_one_does_not() {
    let config = MissionConfig::default();
    // First placed facing out of the arena (+y), then seen to face in (-y).
    let free = (0..DROP_PLACES.len()).collect();
    let mut d = Delivery::new(421, Colour::Red, gate((0.0, 1.0)), free, &config, 0.0).unwrap();
    assert!(goal(&d).y > 2.0);
    d.follow_gate(gate((0.0, -1.0)), &config);
    let fixed = goal(&d);
    assert!(
        (fixed.y - (2.0 - config.drop_staging)).abs() < 1e-9,
        "{fixed:?}"
    );
    // A turn of 10° is inside the estimate's wobble: the plan stands.
    let (s, c) = (-100f64).to_radians().sin_cos();
    d.follow_gate(gate((c, s)), &config);
    assert_eq!(goal(&d), fixed);
}

#[test]
fn once_every_drop_place_had_no_path_each_retry_goes_to_another() {
    use crate::map::costmap::{Costmap, FREE};
    use crate::mission::step::PathStatus;
    use std::collections::BTreeMap;
    let config = MissionConfig::default();
    let map = Costmap::new(200, 200, 0.02, Point2::new(-2.0, -2.0), FREE);
    let free: Vec<usize> = (0..DROP_PLACES.len()).collect();
    let mut d = Delivery::new(421, Colour::Red, gate((0.0, -1.0)), free, &config, 0.0).unwrap();
    let (landmarks, no_path) = (BTreeMap::new(), PathStatus::NoPath("walled in".into()));
    let (mut ctx, mut log) = (Ctx::default(), Vec::new());
    // Each retry's goal, in order, once the leg is turning and retrying.
    let mut retried_to: Vec<Point2> = Vec::new();
    let mut t = 0.0;
    while t < 120.0 && retried_to.len() < 2 * DROP_PLACES.len() {
        let inputs = Inputs {
            t,
            pose: crate::geometry::Pose2::new(0.0, 0.0, 0.0),
            landmarks: &landmarks,
            seen: &[],
            camera_frame: false,
            gripper: None,
            path: &no_path,
            map: &map,
            occupied: &[],
            scan: &[],
            position_std: 0.01,
            localized: false,
            arm: None,
            can_pick: true,
        };
        let event = d.step(&inputs, &config, &mut ctx, None, &mut log);
        assert!(!matches!(event, DropEvent::GiveUp), "gave up at {t}");
        if let Stage::Travel(leg) = &d.stage
            && leg.retrying().is_some()
            && retried_to.last() != Some(&leg.goal)
        {
            retried_to.push(leg.goal);
        }
        t += 0.1;
    }
    assert!(retried_to.len() >= DROP_PLACES.len(), "{log:?}");
    for pair in retried_to.windows(2) {
        assert!(
            pair[0].distance(pair[1]) > 0.05,
            "retried in place: {pair:?}"
        );
    }
    let distinct = (retried_to.iter().enumerate())
        .filter(|(i, p)| retried_to[..*i].iter().all(|q| q.distance(**p) > 1e-6))
        .count();
    assert_eq!(distinct, DROP_PLACES.len(), "{retried_to:?}");
}
