//! The mission's recoveries driven by scripted inputs (seed 001 "Failure Modes &
//! Recovery"): empty gripper, block lost, robot lost, no path, stuck.

use crate::mission_rig;

use mission_rig::{DT, Rig, all_free, config, half_known, plan_to};
use navdeck::data::GripperCommand;
use navdeck::geometry::Point2;
use navdeck::mission::MissionConfig;
use navdeck::mission::step::{Motion, PathStatus};

#[test]
fn an_empty_gripper_reopens_and_retries_once_then_demotes_the_block() {
    let mut rig = Rig::new(config(4), all_free());
    rig.add_block(421, 1.0, 0.0);
    rig.add_red_gate();
    // The block is really 5 cm to the side of where the map has it: the jaws miss.
    rig.blocks[0].1 = Point2::new(1.0, 0.05);
    rig.until(800, |_, r| r.logged("Gripper closed on nothing"));
    assert!(rig.mission.state_label().starts_with("reopen"));
    rig.until(300, |_, r| r.logged("back to a potential block"));
    assert_eq!(
        rig.commands,
        [
            GripperCommand::Open,
            GripperCommand::Close,
            GripperCommand::Open,
            GripperCommand::Close
        ]
    );
    assert!(rig.mission.recoveries() >= 2);
    assert!(rig.mission.timeline()[0].2.is_none(), "never picked");
    // Not straight back to the same block: it waits as a potential one.
    let out = rig.step();
    assert!(
        !rig.mission
            .state_label()
            .contains("travel to red block 421"),
        "{}",
        rig.mission.state_label()
    );
    assert!(out.ignore_markers.is_empty());
}

#[test]
fn a_block_below_the_camera_is_approached_on_its_estimate_not_lost() {
    // The camera loses a block's markers 0.23 m ahead (under its view), and the
    // approach starts 0.30 m out: it sees nothing for the whole approach, yet goes on.
    let mut cfg = config(4);
    cfg.blind_distance = Some(0.23);
    let mut rig = Rig::new(cfg, all_free());
    rig.add_block(421, 1.0, 0.0);
    rig.add_red_gate();
    rig.until(600, |_, r| {
        r.mission.state_label() == "approach red block 421"
    });
    rig.seen = vec![1];
    rig.until(400, |_, r| {
        r.commands.last() == Some(&GripperCommand::Close)
    });
    assert!(!rig.logged("during the approach"), "{:?}", rig.log);
    rig.until(100, |_, r| r.logged("Picked up red block 421"));
}

#[test]
fn a_block_the_lidar_outlines_is_not_lost_when_its_markers_face_away() {
    // Its markers sit on two faces only; from this side the camera reads neither, and the
    // lidar's outline says it is still there.
    let mut rig = Rig::new(config(4), all_free());
    rig.lidar = true;
    rig.add_block(421, 1.0, 0.0);
    rig.add_red_gate();
    rig.until(600, |_, r| r.mission.state_label() == "face red block 421");
    rig.seen = vec![1];
    rig.until(200, |_, r| r.logged("Picked up red block 421"));
    assert!(!rig.logged("during the approach"), "{:?}", rig.log);
}

#[test]
fn the_creep_aims_where_the_lidar_outlines_the_block_not_at_its_markers() {
    // The markers put the block 5 cm to the side of where it is: without a scan the jaws
    // miss it (the first test); the scan's outline takes them to it at the first close.
    let mut rig = Rig::new(config(4), all_free());
    rig.lidar = true;
    rig.add_block(421, 1.0, 0.0);
    rig.add_red_gate();
    rig.blocks[0].1 = Point2::new(1.0, 0.05);
    rig.until(800, |_, r| r.logged("Picked up red block 421"));
    assert!(!rig.logged("closed on nothing"), "{:?}", rig.log);
    assert_eq!(rig.commands, [GripperCommand::Open, GripperCommand::Close]);
}

#[test]
fn a_block_unseen_in_view_for_3_s_during_the_approach_is_demoted() {
    // Staged 0.5 m out, the approach takes longer than the 3 s (from 0.3 m it is over in
    // under 3 s, the block picked whether seen or not).
    let staged_further = MissionConfig {
        staging_distance: 0.5,
        ..config(4)
    };
    let mut rig = Rig::new(staged_further, all_free());
    rig.add_block(421, 1.0, 0.0);
    rig.add_red_gate();
    rig.until(600, |_, r| r.mission.state_label() == "face red block 421");
    rig.seen = vec![1];
    let start = rig.t;
    rig.until(100, |_, r| {
        r.logged("Lost red block 421 during the approach")
    });
    let took = rig.t - start;
    assert!((3.0..3.3).contains(&took), "{took}");
    assert!(!rig.mission.state_label().contains("approach red block"));
    assert_eq!(
        rig.mission.known_blocks(),
        0,
        "demoted to a potential block"
    );
    // It stands in the block's ring, facing it: it backs away before planning anew.
    let at = rig.pose.position();
    let backed = rig.until(
        5,
        |out, _| matches!(out.motion, Motion::Drive(t) if t.linear < 0.0),
    );
    assert!(matches!(backed.motion, Motion::Drive(_)));
    rig.until(
        40,
        |out, _| !matches!(out.motion, Motion::Drive(t) if t.linear < 0.0),
    );
    let away = rig.pose.position().distance(at);
    assert!((0.15..0.25).contains(&away), "backed {away:.3} m");
}

#[test]
fn a_lost_robot_scans_after_10_s_and_hands_over_after_30_s() {
    let mut rig = Rig::new(config(4), half_known());
    rig.auto = false;
    rig.until(200, |out, _| plan_to(out).is_some());
    rig.path = PathStatus::Following { remaining: 0.9 };
    rig.seen.clear();
    rig.position_std = 0.1;
    let dark = rig.t;
    let out = rig.until(200, |out, _| matches!(out.motion, Motion::Drive(_)));
    assert!(rig.logged("No landmarks for 10 s - rotating to scan"));
    assert!(rig.t - dark >= 10.0 - 1.0 && rig.t - dark <= 10.2);
    let Motion::Drive(tw) = out.motion else {
        unreachable!()
    };
    assert!(tw.linear == 0.0 && tw.angular > 0.0);
    let out = rig.until(300, |out, _| out.to_manual);
    assert!(rig.logged("Robot lost: no landmarks for 30 s - switching to manual"));
    assert!((rig.t - dark - 30.0).abs() < 1.5, "{}", rig.t - dark);
    assert_eq!(out.motion, Motion::Stop);
    assert!(rig.mission.recoveries() >= 1);
}

#[test]
fn a_lost_robot_that_sees_a_marker_again_goes_back_to_choosing() {
    let mut rig = Rig::new(config(4), half_known());
    rig.auto = false;
    rig.until(200, |out, _| plan_to(out).is_some());
    rig.path = PathStatus::Following { remaining: 0.9 };
    rig.seen.clear();
    rig.position_std = 0.1;
    rig.until(200, |_, r| r.mission.state_label().starts_with("lost"));
    rig.seen = vec![1];
    let out = rig.until(20, |out, _| plan_to(out).is_some());
    assert!(!out.to_manual);
    assert!(rig.logged("Landmarks back in view"));
}

#[test]
fn an_unreachable_target_is_given_up_for_the_next_and_all_are_retried_after_turns() {
    let mut rig = Rig::new(config(4), half_known());
    rig.auto = false;
    rig.until(200, |out, _| plan_to(out).is_some());
    let first = rig.plans.len();
    // Every plan fails from now on.
    rig.path = PathStatus::NoPath("goal in an obstacle".into());
    rig.until(200, |_, r| r.plans.len() == first + 1);
    assert!(
        rig.logged("giving it up for the next target"),
        "{:?}",
        rig.log
    );
    let out = rig.until(20_000, |out, _| out.to_manual);
    // Seed 001 "Path Planning Failure": a 10° turn before trying the given-up ones again.
    assert!(rig.logged("turning 10° and trying them again (1/3)"));
    assert!(rig.logged("(3/3)"));
    assert!(rig.logged("Exploration complete"));
    assert!(rig.logged("with 0/4 blocks delivered - switching to manual"));
    // The one target, then three rounds of trying it again.
    assert_eq!(rig.plans.len(), first + 3, "{:?}", rig.plans);
    assert_eq!(out.motion, Motion::Stop);
    let gaps = rig.plans.windows(2).map(|w| w[1].0 - w[0].0);
    assert!(gaps.clone().all(|g| g >= 0.5 - 1e-9), "cooldown");
}

#[test]
fn a_stuck_path_is_replanned_after_30_s_and_dropped_paths_respect_the_cooldown() {
    let mut rig = Rig::new(config(4), half_known());
    rig.auto = false;
    rig.until(200, |out, _| plan_to(out).is_some());
    let asked = rig.t - DT;
    // Creeping: 4 cm in 30 s is no progress. The robot backs up for back_off_time (2 s),
    // then plans again.
    let mut backing = Vec::new();
    for i in 0..400 {
        rig.path = PathStatus::Following {
            remaining: 0.9 - 0.0001 * i as f64,
        };
        let out = rig.step();
        if let Motion::Drive(twist) = out.motion
            && twist.linear < 0.0
        {
            backing.push(rig.t - DT);
        }
        if plan_to(&out).is_some() {
            break;
        }
    }
    let began = backing.first().copied().expect("the robot backs up");
    assert!((began - asked - 30.0).abs() < 0.15, "{}", began - asked);
    let replanned = rig.plans.last().unwrap().0;
    assert!(
        (replanned - asked - 32.0).abs() < 0.15,
        "{}",
        replanned - asked
    );
    assert!(rig.logged("Stuck: no progress for 30 s - backing up"));
    assert_eq!(rig.mission.replans(), 1);
    // Progress resets the clock: steady progress never replans.
    let n = rig.plans.len();
    for i in 0..400 {
        rig.path = PathStatus::Following {
            remaining: 0.9 - 0.002 * i as f64,
        };
        rig.step();
    }
    assert_eq!(rig.plans.len(), n);
    // The console drops the path each time: plan requests at most every 0.5 s.
    rig.path = PathStatus::Idle;
    for _ in 0..30 {
        rig.step();
    }
    let times: Vec<f64> = rig.plans[n..].iter().map(|p| p.0).collect();
    assert!(times.len() >= 4, "{times:?}");
    assert!(
        times.windows(2).all(|w| w[1] - w[0] >= 0.5 - 1e-9),
        "{times:?}"
    );
}

#[test]
fn with_other_targets_left_the_next_one_is_tried_at_once() {
    // All free but not yet looked at: many places to go and look.
    let config = navdeck::mission::MissionConfig {
        total_blocks: 4,
        ..navdeck::mission::MissionConfig::default()
    };
    let mut rig = Rig::new(config, all_free());
    rig.auto = false;
    rig.until(400, |out, _| plan_to(out).is_some());
    let first = rig.plans.len();
    rig.path = PathStatus::NoPath("goal in an obstacle".into());
    let heading = rig.pose.theta;
    rig.until(50, |_, r| r.plans.len() == first + 1);
    let (a, b) = (&rig.plans[first - 1].2, &rig.plans[first].2);
    assert_ne!(a, b, "a different target: {:?}", rig.log);
    assert_eq!(
        rig.pose.theta, heading,
        "no turn while other targets are left"
    );
}

#[test]
fn a_robot_lost_for_30_s_drives_back_to_the_nearest_landmark_and_resumes_on_seeing_one() {
    let mut rig = Rig::new(config(4), half_known());
    rig.landmarks
        .insert(7, navdeck::geometry::Point2::new(-1.5, 0.0));
    rig.landmarks
        .insert(8, navdeck::geometry::Point2::new(1.9, 1.9));
    rig.auto = false;
    rig.until(200, |out, _| plan_to(out).is_some());
    rig.path = PathStatus::Following { remaining: 0.9 };
    rig.seen.clear();
    rig.position_std = 0.1;
    let out = rig.until(400, |out, _| plan_to(out).is_some() || out.to_manual);
    assert!(!out.to_manual, "{:?}", rig.log);
    assert!(rig.logged("going back to marker 7, the nearest seen"));
    let (goal, label) = plan_to(&out).unwrap();
    assert_eq!(label, "marker 7");
    let robot = rig.pose.position();
    let at = navdeck::geometry::Point2::new(-1.5, 0.0);
    assert!(
        (goal.distance(at) - 0.5).abs() < 1e-9,
        "0.5 m in front of it"
    );
    assert!(goal.distance(robot) < at.distance(robot));
    // A marker in view again: back to exploring.
    rig.seen = vec![7];
    rig.until(20, |_, r| r.logged("Landmarks back in view"));
    assert!(!rig.mission.state_label().starts_with("lost"));
}

#[test]
fn no_marker_for_a_while_is_not_lost_while_the_filter_is_sure_of_the_position() {
    let mut rig = Rig::new(config(4), half_known());
    rig.auto = false;
    rig.until(200, |out, _| plan_to(out).is_some());
    rig.path = PathStatus::Following { remaining: 0.9 };
    rig.seen.clear();
    // Crossing open space: no marker, but odometry keeps the position within 3 cm.
    rig.position_std = 0.03;
    for _ in 0..300 {
        rig.step();
    }
    assert!(!rig.logged("No landmarks"), "{:?}", rig.log);
    assert!(!rig.mission.state_label().starts_with("lost"));
    // The uncertainty grows past 7 cm: now it is lost, and scans.
    rig.position_std = 0.08;
    rig.until(20, |_, r| r.mission.state_label().starts_with("lost"));
    assert!(rig.logged("No landmarks for 10 s - rotating to scan"));
    assert!(
        rig.mission.reason().contains("position unsure"),
        "{}",
        rig.mission.reason()
    );
}

#[test]
fn a_lost_robot_goes_back_to_a_fixed_marker_not_a_block_and_scans_there_before_handing_over() {
    let mut rig = Rig::new(config(4), half_known());
    // A block marker (421) nearer than the wall marker (7).
    rig.landmarks
        .insert(7, navdeck::geometry::Point2::new(-1.5, 0.0));
    rig.landmarks
        .insert(421, navdeck::geometry::Point2::new(0.3, 0.0));
    rig.until(200, |out, _| plan_to(out).is_some());
    rig.seen.clear();
    rig.position_std = 0.1;
    rig.until(600, |out, _| {
        plan_to(out).is_some_and(|(_, label)| label == "marker 7") || out.to_manual
    });
    assert!(
        rig.logged("going back to marker 7, the nearest seen"),
        "{:?}",
        rig.log
    );
    // It gets there (the rig drives plans), sees nothing, scans, then hands over.
    let arrived = rig.t;
    let out = rig.until(900, |out, _| out.to_manual);
    assert!(out.to_manual);
    assert!(
        rig.t - arrived >= 20.0,
        "scanned there first: {:.1} s",
        rig.t - arrived
    );
    assert!(rig.logged("no landmarks in view even after going back and scanning"));
}

/// With an arm, a close on nothing lifts the empty arm before the robot backs away, and
/// the retry reaches for the block afresh.
#[test]
fn with_an_arm_an_empty_grip_lifts_backs_up_and_reaches_again() {
    let mut rig = Rig::new(config(4), all_free()).with_arm();
    rig.add_block(421, 1.0, 0.0);
    rig.add_red_gate();
    // The block is really 5 cm to the side of where the map has it: the jaws miss.
    rig.blocks[0].1 = Point2::new(1.0, 0.05);
    rig.until(800, |_, r| r.logged("Gripper closed on nothing"));
    let moves = rig.arm_moves.len();
    rig.until(100, |_, r| r.mission.state_label().starts_with("back up"));
    assert_eq!(rig.arm_moves.len(), moves + 1, "the arm goes up first");
    let home = navdeck::arm::ArmConfig::default().poses.home;
    assert_eq!(rig.arm.as_ref().unwrap().1, home);
    rig.until(300, |_, r| r.logged("back to a potential block"));
    let reaches = rig.log.iter().filter(|l| l.contains("Arm above")).count();
    assert_eq!(reaches, 2, "{:?}", rig.log);
}
