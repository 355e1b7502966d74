//! Where a block is put down and when it counts: drop places that exist (another one
//! when there is no path, never the same point again), a block let go outside its gate
//! or not found where it was let go is not delivered, and in the twin the mission's count
//! equals the twin's own on worlds with many blocks of one colour.

use crate::common;
use crate::mission_rig;

use common::generated_mission;
use mission_rig::{Rig, all_free, config, plan_to};
use navdeck::geometry::Point2;
use navdeck::map::costmap::LETHAL;
use navdeck::mission::drop_places::DROP_PLACES;
use navdeck::mission::step::PathStatus;

/// A rig holding red block 421, on its way to the red gate at (-1, 1) facing +x.
fn heading_for_the_gate(rig: &mut Rig) -> Point2 {
    rig.add_block(421, 1.0, 0.0);
    rig.add_red_gate();
    let out = rig.until(600, |out, _| {
        plan_to(out).is_some_and(|p| p.1 == "red gate")
    });
    plan_to(&out).unwrap().0
}

#[test]
fn a_drop_place_with_no_path_is_rederived_and_never_asked_for_twice_in_a_row() {
    let mut rig = Rig::new(config(4), all_free());
    let first = heading_for_the_gate(&mut rig);
    let asked = rig.plans.len();
    rig.auto = false;
    rig.path = PathStatus::NoPath("goal (-0.6, 1.0) is unreachable".into());
    rig.until(400, |_, r| {
        r.logged("No path to any of the 9 drop places free at the red gate")
    });
    let goals: Vec<Point2> = (rig.plans[asked - 1..].iter())
        .filter(|p| p.2 == "red gate")
        .map(|p| p.1)
        .collect();
    assert_eq!(goals[0], first);
    assert!(goals.len() >= DROP_PLACES.len(), "{goals:?}");
    // Every free drop place once, each a different point, before any is asked again.
    for (i, a) in goals[..DROP_PLACES.len()].iter().enumerate() {
        for b in &goals[..i] {
            assert!(a.distance(*b) > 0.04, "{a:?} asked twice: {goals:?}");
        }
        // Every one in front of the gate (x = -1), inside the arena side.
        assert!(a.x > -1.0 + 0.35, "{a:?}");
    }
    assert!(rig.logged("No path to drop place 1 of the red gate (goal (-0.6, 1.0) is unreachable) - trying drop place 2"));
    assert!(!rig.mission.is_done());
}

#[test]
fn a_drop_place_the_map_shows_in_a_wall_is_passed_over_before_any_plan() {
    let mut map = all_free();
    // The gate's wall along x = -1, closed behind.
    for y in 0..map.height {
        for x in 0..=10 {
            map.set(x, y, LETHAL);
        }
    }
    // A box right where the first drop place's staging point is: (-0.6, 1.0).
    for y in 29..=30 {
        for x in 13..=14 {
            map.set(x, y, LETHAL);
        }
    }
    let mut rig = Rig::new(config(4), map);
    let goal = heading_for_the_gate(&mut rig);
    assert!(goal.distance(Point2::new(-0.6, 1.0)) > 0.05, "{goal:?}");
    assert!(
        rig.logged("Drop place 1 of the red gate lies in a wall or ring on the map"),
        "{:?}",
        rig.log
    );
}

#[test]
fn a_block_let_go_away_from_its_gate_is_not_counted_and_is_looked_for_again() {
    let mut rig = Rig::new(config(4), all_free());
    heading_for_the_gate(&mut rig);
    rig.until(400, |_, r| r.mission.state_label().starts_with("drive"));
    // The gate turns out to be 0.5 m further along its wall than the robot drove to.
    rig.landmarks.insert(401, Point2::new(-1.0, 1.65));
    rig.landmarks.insert(402, Point2::new(-1.0, 1.35));
    rig.until(400, |_, r| r.logged("not delivered"));
    assert!(
        rig.logged("red block 421 not delivered: let go 0.5"),
        "{:?}",
        rig.log
    );
    assert_eq!(rig.mission.delivered(), 0);
    assert!(!rig.logged("Delivered red block 421"));
    assert!(rig.mission.timeline().iter().all(|e| e.3.is_none()));
}

#[test]
fn a_block_neither_the_lidar_nor_the_camera_finds_where_it_was_let_go_is_not_counted() {
    let mut rig = Rig::new(config(4), all_free());
    heading_for_the_gate(&mut rig);
    rig.until(400, |_, r| r.mission.state_label().starts_with("back off"));
    // A lidar that maps nothing there, and a camera that does not see the block.
    rig.occupied = vec![false; rig.map.width * rig.map.height];
    rig.seen.retain(|&id| id != 421 && id != 422);
    rig.until(400, |_, r| r.logged("not delivered"));
    assert!(
        rig.logged("neither the lidar nor the camera finds it where it was let go"),
        "{:?}",
        rig.log
    );
    assert_eq!(rig.mission.delivered(), 0);
    // With nothing else to explore, the robot goes back to look for it where it let go.
    let look = (rig.plans.iter()).find(|p| p.2.starts_with("unexplained object"));
    let goal = look.expect("a look where it was let go").1;
    assert!(goal.distance(Point2::new(-0.8, 1.0)) < 0.6, "{goal:?}");
    assert!(!rig.logged("Exploration complete"), "{:?}", rig.log);
}

#[test]
fn a_block_the_newest_scan_shows_where_it_was_let_go_counts_before_the_map_has_it() {
    let mut rig = Rig::new(config(4), all_free());
    heading_for_the_gate(&mut rig);
    rig.until(400, |_, r| r.mission.state_label().starts_with("back off"));
    // The map has not folded in a scan since, and the block's markers face away; the
    // lidar's newest scan shows it where the jaws let it go, 0.10 m ahead of them.
    rig.occupied = vec![false; rig.map.width * rig.map.height];
    rig.seen.retain(|&id| id != 421 && id != 422);
    rig.blocks[0].1 = rig.pose.transform_point(Point2::new(0.10, 0.0));
    rig.lidar = true;
    rig.until(400, |_, r| r.logged("Delivered red block 421"));
    assert!(!rig.logged("not delivered"), "{:?}", rig.log);
    assert_eq!(rig.mission.delivered(), 1);
}

/// Worlds where a third, fourth, ... block of one colour goes to its gate: the mission's
/// count is the twin's, and every block is at its gate. Boxes seed 52's eight blocks of
/// one colour filled its gate's places only once each creep ended on its place's line.
#[test]
fn with_many_blocks_of_one_colour_every_delivery_counted_is_at_its_gate() {
    let eight = [
        "--colours",
        "one",
        "--blocks",
        "8",
        "--size",
        "5.8,4.9",
        "--marker-spacing",
        "0.94",
    ];
    for (style, seed, extra) in [
        ("boxes", "3", &["--colours", "one", "--blocks", "6"][..]),
        ("boxes", "52", &eight[..]),
        ("boxes", "8", &["--colours", "random", "--blocks", "8"][..]),
        (
            "rooms",
            "4",
            &["--colours", "one", "--blocks", "7", "--size", "6,5"][..],
        ),
    ] {
        let r = generated_mission(style, seed, extra);
        let total = r["total"].clone();
        assert_eq!(
            r["delivered"], r["true_delivered"],
            "{style} {seed} {extra:?}: {r}"
        );
        assert_eq!(r["true_delivered"], total, "{style} {seed} {extra:?}: {r}");
        assert_eq!(r["outcome"], "delivered all", "{style} {seed} {extra:?}");
    }
}
