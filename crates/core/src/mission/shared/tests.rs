//! One robot's exploration in a fleet: it leaves the ground another robot claims, takes
//! what the others explored as explored, and waits while all that is left is claimed.

use super::super::coverage::Coverage;
use super::super::fleet_explored::ExploredLayer;
use super::super::phase::Phase;
use super::super::step::{Inputs, PathStatus};
use super::super::{Mission, MissionConfig};
use super::FleetShare;
use crate::geometry::{Point2, Pose2};
use crate::map::costmap::{Costmap, FREE, NO_INFORMATION};
use std::collections::BTreeMap;
use std::sync::Arc;

/// 6 m x 2 m at 5 cm: mapped free from x = 0.5 to 5.5 m, unknown at both ends (a
/// frontier at each).
fn corridor() -> Costmap {
    let mut map = Costmap::new(120, 40, 0.05, Point2::new(0.0, 0.0), NO_INFORMATION);
    for y in 0..40 {
        for x in 10..110 {
            map.set(x, y, FREE);
        }
    }
    map
}

/// The robot at x = 2.5 m, 2 m from the west frontier and 3 m from the east one.
const ROBOT: Pose2 = Pose2 {
    x: 2.5,
    y: 1.0,
    theta: 0.0,
};

/// A mission about to choose, and what it chose after one step on `map`, with its log.
fn choose(mission: &mut Mission, map: &Costmap) -> String {
    mission.phase = Phase::Choose;
    let landmarks = BTreeMap::new();
    let out = mission.step(&Inputs {
        t: 1.0,
        pose: ROBOT,
        landmarks: &landmarks,
        seen: &[],
        camera_frame: false,
        gripper: None,
        path: &PathStatus::Idle,
        map,
        occupied: &[],
        scan: &[],
        position_std: 0.0,
        localized: true,
        arm: None,
        can_pick: true,
    });
    let log: Vec<String> = out.log.into_iter().map(|l| l.1).collect();
    log.join("\n")
}

/// Another robot's layer: it mapped all but the west end and its camera looked at
/// everything it mapped.
fn east_explored() -> Arc<ExploredLayer> {
    let mut map = Costmap::new(120, 40, 0.05, Point2::new(0.0, 0.0), FREE);
    for y in 0..40 {
        for x in 0..10 {
            map.set(x, y, NO_INFORMATION);
        }
    }
    let mut seen = Coverage::default();
    for i in 0..12 {
        for k in 0..8 {
            let heading = f64::from(k) * std::f64::consts::FRAC_PI_4;
            let pose = Pose2::new(0.75 + 0.5 * f64::from(i), 1.0, heading);
            seen.look(&map, pose, 1.5, 1.0);
        }
    }
    Arc::new(ExploredLayer::new(&map, &seen))
}

/// The fleet's word: goals `taken` with 1.5 m of ground each, and the others' layers.
fn share(taken: Vec<Point2>, others: Vec<Arc<ExploredLayer>>) -> FleetShare {
    FleetShare {
        taken,
        reach: 1.5,
        others,
        peers: Vec::new(),
    }
}

#[test]
fn a_robot_picks_the_frontier_no_other_robot_claims() {
    let map = corridor();
    let mut alone = Mission::new(MissionConfig::default(), 0.0);
    choose(&mut alone, &map);
    let west = alone.frontier_claim().expect("a frontier to explore");
    assert!(west.x < 1.0, "the nearer, west frontier: {west:?}");
    // Another robot claims the west frontier: this one goes east, out of its ground.
    let mut second = Mission::new(MissionConfig::default(), 0.0);
    second.share_exploration(share(vec![west], Vec::new()));
    choose(&mut second, &map);
    let east = second.frontier_claim().expect("a frontier to explore");
    assert!(east.x > 5.0, "the east frontier: {east:?}");
    // A goal that falls in ground claimed since is dropped and chosen again.
    let mut late = Mission::new(MissionConfig::default(), 0.0);
    choose(&mut late, &map);
    late.share_exploration(share(vec![Point2::new(west.x + 0.2, west.y)], Vec::new()));
    assert_eq!(late.frontier_claim(), None);
}

#[test]
fn what_another_robot_explored_is_no_target_and_claimed_ground_is_waited_for() {
    let map = corridor();
    // The other robot mapped and looked at everything east: only the west is left.
    let mut mission = Mission::new(MissionConfig::default(), 0.0);
    mission.share_exploration(share(Vec::new(), vec![east_explored()]));
    choose(&mut mission, &map);
    let goal = mission.frontier_claim().expect("the west frontier");
    assert!(goal.x < 1.0, "{goal:?}");
    // With the west claimed by another robot, nothing is this robot's: it waits, turning,
    // and does not call exploration complete.
    let mut mission = Mission::new(MissionConfig::default(), 0.0);
    mission.share_exploration(share(vec![goal], vec![east_explored()]));
    let log = choose(&mut mission, &map);
    assert!(log.contains("another robot's - waiting"), "{log}");
    assert!(!log.contains("Exploration complete"), "{log}");
    assert!(matches!(mission.phase, Phase::Scan { .. }));
}
