//! The mission state machine driven by scripted inputs: the initial scan, choosing
//! targets, the pick-up and delivery sequences and finishing.

use crate::mission_rig;

use mission_rig::{DT, Rig, all_free, all_seeing, config, half_known, plan_to};
use navdeck::data::GripperCommand;
use navdeck::geometry::{Point2, wrap_angle};
use navdeck::mission::step::{Motion, PathStatus};
use navdeck::mission::{MissionConfig, TargetRule};
use std::f64::consts::PI;

#[test]
fn the_initial_scan_turns_a_full_turn_then_plans_to_a_frontier() {
    let mut rig = Rig::new(config(4), half_known());
    rig.auto = false;
    let out = rig.until(200, |out, _| plan_to(out).is_some());
    let turned = rig.t - DT; // time spent turning: the last step planned
    assert!(rig.logged("Initial rotation scan"));
    assert!(
        turned >= 2.0 * PI / 0.6,
        "planned after {turned:.1} s, before a full turn"
    );
    assert!(turned < 2.0 * PI / 0.6 + 0.5);
    let (goal, label) = plan_to(&out).unwrap();
    assert!((goal.x - 0.95).abs() < 1e-9, "{goal:?}");
    assert!(label.starts_with("frontier"), "{label}");
    assert!(rig.logged("Thinking path to frontier"));
    assert!(rig.mission.state_label().starts_with("explore frontier"));
    // While the path is followed: Follow, and no second PlanTo.
    rig.path = PathStatus::Following { remaining: 0.9 };
    for _ in 0..20 {
        assert_eq!(rig.step().motion, Motion::Follow);
    }
}

#[test]
fn a_deliverable_block_beats_exploring_and_interrupts_it() {
    let mut rig = Rig::new(config(4), half_known());
    rig.auto = false;
    rig.until(200, |out, _| plan_to(out).is_some());
    rig.path = PathStatus::Following { remaining: 0.9 };
    for _ in 0..10 {
        rig.step();
    }
    // Block and gate come into view while following the frontier path.
    rig.add_block(421, 1.0, 0.0);
    rig.add_red_gate();
    let out = rig.step();
    let (goal, label) = plan_to(&out).expect("plans to the block at once");
    assert_eq!(label, "red block 421");
    assert!(goal.distance(Point2::new(0.7, 0.0)) < 1e-6, "{goal:?}");
    assert!(rig.logged("Found red block 421"));
    assert!(rig.logged("Found red gate"));
    assert!(rig.logged("Found red gate and blocks - planning a delivery"));
    assert_eq!(rig.mission.state_label(), "travel to red block 421");
    assert_eq!(rig.mission.known_blocks(), 1);

    // Known from the start: the first plan after the scan goes to the block.
    let mut rig = Rig::new(config(4), half_known());
    rig.add_block(421, 1.0, 0.0);
    rig.add_red_gate();
    let out = rig.until(200, |out, _| plan_to(out).is_some());
    assert_eq!(plan_to(&out).unwrap().1, "red block 421");
}

/// Runs from the start to the delivery plan; returns the rig.
fn picked_up(total: u32) -> Rig {
    let mut rig = Rig::new(config(total), all_free());
    rig.add_block(421, 1.0, 0.0);
    rig.add_red_gate();
    rig.until(600, |out, _| {
        plan_to(out).is_some_and(|p| p.1 == "red gate")
    });
    rig
}

#[test]
fn the_pick_up_sequence_opens_faces_approaches_closes_and_heads_for_the_gate() {
    let mut rig = Rig::new(config(4), all_free());
    rig.add_block(421, 1.0, 0.0);
    rig.add_red_gate();
    rig.until(200, |out, _| plan_to(out).is_some());
    rig.until(100, |_, r| {
        r.mission.state_label() == "open gripper for red block 421"
    });
    assert!(rig.pose.position().distance(Point2::new(0.7, 0.0)) < 1e-6);
    assert!(rig.logged("Path found") && rig.logged("Following path to red block 421"));
    assert_eq!(rig.commands, [GripperCommand::Open]);
    // Turn the robot away: it must face the block again before approaching.
    rig.pose.theta = 0.5;
    rig.until(50, |_, r| r.mission.state_label() == "face red block 421");
    rig.until(100, |_, r| {
        r.mission.state_label() == "approach red block 421"
    });
    assert!(rig.pose.theta.abs() < 3f64.to_radians(), "{:?}", rig.pose);
    let out = rig.until(200, |out, _| out.gripper == Some(GripperCommand::Close));
    assert!(out.ignore_markers.is_empty(), "not held yet");
    let ahead = rig.pose.inverse_transform_point(Point2::new(1.0, 0.0));
    assert!(
        (ahead.x - 0.115).abs() < 0.01 && ahead.y.abs() < 0.01,
        "{ahead:?}"
    );
    let out = rig.until(50, |out, _| plan_to(out).is_some());
    let (goal, _) = plan_to(&out).unwrap();
    // The first drop place of the gate at (-1, 1): in front of its centre, 0.4 m out.
    assert!(goal.distance(Point2::new(-0.6, 1.0)) < 1e-9, "{goal:?}");
    assert!(rig.logged("Picked up red block 421"));
    assert_eq!(out.ignore_markers, [421, 422]);
    assert_eq!(rig.commands, [GripperCommand::Open, GripperCommand::Close]);
    let entry = rig.mission.timeline()[0];
    assert_eq!(entry.0, 421);
    assert!(entry.2.is_some() && entry.3.is_none());
}

#[test]
fn the_delivery_sequence_drops_backs_off_and_counts() {
    let mut rig = picked_up(4);
    rig.until(300, |_, r| {
        r.mission.state_label().starts_with("face red gate")
    });
    rig.until(100, |_, r| r.mission.state_label().starts_with("drive"));
    assert!(wrap_angle(rig.pose.theta - PI).abs() < 3f64.to_radians());
    rig.until(200, |out, _| out.gripper == Some(GripperCommand::Open));
    // The first drop place: in front of the gate's centre (-1, 1).
    let place = Point2::new(-1.0, 1.0);
    assert!((rig.pose.position().distance(place) - 0.18).abs() < 0.01);
    let at_drop = rig.pose.position();
    let out = rig.until(100, |out, _| !out.log.is_empty());
    assert!(rig.logged("Delivered red block 421 (1/4)"), "{:?}", rig.log);
    assert!(
        (rig.pose.position().distance(at_drop) - 0.2).abs() < 0.011,
        "backs off 2 s at 0.1 m/s"
    );
    assert_eq!(rig.mission.delivered(), 1);
    assert_eq!(
        out.ignore_markers,
        [421, 422],
        "delivered markers stay ignored"
    );
    assert_eq!(
        rig.commands,
        [
            GripperCommand::Open,
            GripperCommand::Close,
            GripperCommand::Open
        ]
    );
    assert!(rig.mission.timeline()[0].3.is_some());
    // Nothing else to do in an explored arena with 1 of 4 blocks: manual.
    let out = rig.step();
    assert!(out.to_manual, "{:?}", rig.log);
    assert!(rig.logged("Exploration complete"));
    assert!(!rig.mission.is_done());
}

#[test]
fn the_mission_is_done_after_total_blocks_deliveries() {
    let mut rig = Rig::new(config(2), all_free());
    rig.add_block(421, 1.0, 0.0);
    rig.add_block(423, 1.0, -0.6);
    rig.add_red_gate();
    rig.until(3000, |_, r| r.mission.is_done());
    assert_eq!(rig.mission.delivered(), 2);
    assert!(rig.logged("Delivered red block 423 (2/2)"), "{:?}", rig.log);
    assert!(rig.logged("All 2 blocks delivered - mission complete"));
    let timeline = rig.mission.timeline();
    assert_eq!(timeline.len(), 2);
    assert!(timeline.iter().all(|e| e.2.is_some() && e.3.is_some()));
    let out = rig.step();
    assert_eq!(out.motion, Motion::Stop);
    assert!(!out.to_manual);
    let mut ignored = out.ignore_markers.clone();
    ignored.sort();
    assert_eq!(ignored, [421, 422, 423, 424]);
    assert_eq!(rig.mission.state_label(), "done");
}

#[test]
fn the_marker_rule_visits_the_furthest_markers_and_the_frontier_rule_needs_no_markers() {
    let config = MissionConfig {
        target_rule: TargetRule::Markers,
        total_blocks: 4,
        ..all_seeing()
    };
    let mut rig = Rig::new(config, all_free());
    rig.landmarks.insert(1, Point2::new(1.5, 0.0));
    rig.landmarks.insert(2, Point2::new(2.0, 0.5));
    let out = rig.until(200, |out, _| plan_to(out).is_some());
    let (goal, label) = plan_to(&out).unwrap();
    assert_eq!(label, "marker 2");
    let stop = Point2::new(2.0, 0.5);
    assert!(
        (goal.distance(stop) - 0.3).abs() < 1e-9,
        "short of the wall"
    );
    rig.until(400, |out, _| plan_to(out).is_some());
    assert_eq!(rig.plans.last().unwrap().2, "marker 1");
    let out = rig.until(400, |out, _| out.to_manual);
    assert!(rig.logged("Exploration complete"));
    assert!(rig.logged("with 0/4 blocks delivered - switching to manual"));
    assert!(out.to_manual && !rig.mission.is_done());
    // A known map the camera has taken in: the frontier rule has nowhere to go, and does
    // not wander from marker to marker.
    let config = MissionConfig {
        total_blocks: 4,
        ..all_seeing()
    };
    let mut rig = Rig::new(config, all_free());
    rig.landmarks.insert(1, Point2::new(1.5, 0.0));
    rig.landmarks.insert(2, Point2::new(2.0, 0.5));
    rig.until(400, |out, _| out.to_manual);
    assert!(rig.plans.is_empty(), "{:?}", rig.plans);
    assert!(rig.logged("Exploration complete"));
}

#[test]
fn with_total_blocks_0_every_found_block_is_delivered_then_the_mission_ends() {
    let mut rig = Rig::new(config(0), all_free());
    rig.add_block(421, 1.0, 0.0);
    rig.add_red_gate();
    rig.until(1500, |_, r| r.mission.is_done());
    assert_eq!(rig.mission.delivered(), 1);
    assert!(rig.logged("Delivered red block 421 (1)"), "{:?}", rig.log);
    assert!(rig.logged("Exploration complete"));
}

/// Runs to the moment the gripper closes on block 421, then makes the gripper silent.
fn closing_with_a_silent_gripper() -> Rig {
    let mut rig = Rig::new(config(1), all_free());
    rig.add_block(421, 1.0, 0.0);
    rig.add_red_gate();
    rig.until(600, |out, _| out.gripper == Some(GripperCommand::Close));
    rig.auto = false;
    rig.gripper = None;
    rig
}

#[test]
fn a_gripper_without_feedback_is_trusted_after_the_seed_wait() {
    let mut rig = closing_with_a_silent_gripper();
    // The block in the jaws hides its markers from the camera.
    rig.seen.retain(|id| ![421, 422].contains(id));
    let start = rig.t;
    rig.until(30, |out, _| plan_to(out).is_some());
    assert!((rig.t - start - 1.0).abs() < 0.15, "{}", rig.t - start);
    assert!(rig.logged("Picked up red block 421"));
}

#[test]
fn without_feedback_a_block_still_in_view_is_a_missed_grip() {
    let mut rig = closing_with_a_silent_gripper();
    // Seed 001 "Gripper Failure": the block's markers are still seen after the wait.
    rig.until(30, |out, _| out.gripper == Some(GripperCommand::Open));
    assert!(rig.logged("Gripper closed on nothing - reopening to retry red block 421"));
    assert!(!rig.logged("Picked up red block 421"));
}

#[test]
fn a_small_object_no_marker_explains_is_looked_at_from_four_sides_before_the_end() {
    let mut rig = Rig::new(all_seeing(), all_free());
    // One occupied lidar cell at (1.05, 1.05) on a 0.1 m map.
    rig.occupied = vec![false; rig.map.width * rig.map.height];
    let (cx, cy) = rig.map.cell_of(Point2::new(1.05, 1.05)).unwrap();
    rig.occupied[rig.map.index(cx, cy)] = true;
    rig.until(400, |out, _| plan_to(out).is_some());
    assert_eq!(rig.mission.reason(), "lidar sees it, no marker; look 1/4");
    rig.until(3000, |_, r| r.mission.is_done());
    assert_eq!(rig.mission.reason(), "all explored, every block delivered");
    let object = Point2::new(1.05, 1.05);
    let looks: Vec<Point2> = (rig.plans.iter())
        .filter(|(_, _, label)| label == "unexplained object (1.05, 1.05)")
        .map(|(_, goal, _)| *goal)
        .collect();
    assert_eq!(looks.len(), 4, "{:?}", rig.plans);
    let bearing = |p: Point2| (p.y - object.y).atan2(p.x - object.x);
    for pair in looks.windows(2) {
        let turn = wrap_angle(bearing(pair[1]) - bearing(pair[0]));
        assert!((turn - PI / 2.0).abs() < 1e-9, "a quarter turn on: {turn}");
    }
    assert!(
        (looks[0].distance(object) - 0.45).abs() < 1e-9,
        "1.5 staging distances off"
    );
    assert!(rig.logged("Exploration complete"));
    // A marker on it explains it: no looks.
    let mut rig = Rig::new(all_seeing(), all_free());
    rig.occupied = vec![false; rig.map.width * rig.map.height];
    rig.occupied[rig.map.index(cx, cy)] = true;
    rig.landmarks.insert(7, Point2::new(1.0, 1.05));
    rig.until(3000, |_, r| r.mission.is_done());
    assert!(rig.plans.is_empty(), "{:?}", rig.plans);
}

/// Seed 000's pick with an arm: the robot stops with the block `arm_standoff` ahead of the
/// arm's base, the tool goes above the block, down to it, closes and lifts; at the gate
/// the tool goes down before the jaws open and up again before the robot backs off.
#[test]
fn with_an_arm_the_pick_goes_above_down_close_lift_and_the_drop_is_put_down() {
    let mut rig = Rig::new(config(4), all_free()).with_arm();
    rig.add_block(421, 1.0, 0.0);
    rig.add_red_gate();
    rig.until(800, |out, _| out.gripper == Some(GripperCommand::Close));
    // Stopped short: the block 0.08 m behind the centre's mount plus 0.25 m ahead of it.
    let ahead = rig.pose.inverse_transform_point(Point2::new(1.0, 0.0));
    let mount = navdeck::arm::ArmConfig::default().mount.x;
    assert!(
        (ahead.x - (mount + 0.25)).abs() < 0.01 && ahead.y.abs() < 0.01,
        "{ahead:?}"
    );
    assert!(rig.logged("Arm above red block 421"));
    // Two moves so far: above the block, then down to its middle.
    assert_eq!(rig.arm_moves.len(), 2, "{:?}", rig.arm_moves);
    let [x, y, z] = rig.tool().unwrap();
    assert!(Point2::new(x, y).distance(Point2::new(1.0, 0.0)) < 1e-6);
    assert!(
        (z - 0.025).abs() < 1e-6,
        "the tool at the block's middle: {z}"
    );
    rig.until(100, |out, _| {
        plan_to(out).is_some_and(|p| p.1 == "red gate")
    });
    assert!(rig.logged("Lifting red block 421") && rig.logged("Picked up red block 421"));
    let home = navdeck::arm::ArmConfig::default().poses.home;
    assert_eq!(rig.arm.as_ref().unwrap().1, home, "carried at home");
    // At the gate: lowered to the floor where it is carried, opened, raised, backed off.
    rig.until(800, |out, _| out.gripper == Some(GripperCommand::Open));
    assert!(rig.logged("Lowering red block 421"));
    let [_, _, z] = rig.tool().unwrap();
    assert!((z - 0.025).abs() < 1e-6, "{z}");
    rig.until(300, |_, r| r.logged("Delivered red block 421"));
    assert_eq!(rig.arm.as_ref().unwrap().1, home, "raised again");
    assert_eq!(rig.arm_moves.len(), 5, "above, down, lift, lower, raise");
}
