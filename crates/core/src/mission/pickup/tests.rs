//! Where a pick-up stands to approach its block, and what it aims at on the way in.

use super::*;
use crate::map::costmap::{FREE, LETHAL};

#[test]
fn the_approach_comes_from_where_a_marker_was_read() {
    let map = Costmap::new(200, 200, 0.01, Point2::new(0.0, 0.0), FREE);
    let config = MissionConfig::default();
    let centre = Point2::new(1.0, 1.0);
    let robot = Point2::new(1.8, 1.0);
    // Read from the west; the robot is now east: the camera would see blank faces.
    let read = Some(Point2::new(0.2, 1.0));
    let p = staging_point(centre, read, robot, &map, &config);
    assert!(
        (p.x - 0.7).abs() < 1e-9 && (p.y - 1.0).abs() < 1e-9,
        "{p:?}"
    );
    // Never read (a potential block from the lidar): from the robot's side.
    let p = staging_point(centre, None, robot, &map, &config);
    assert!((p.x - 1.3).abs() < 1e-9, "{p:?}");
}

#[test]
fn a_blocked_side_turns_the_approach_in_thirty_degree_steps() {
    let mut map = Costmap::new(200, 200, 0.01, Point2::new(0.0, 0.0), FREE);
    // A wall 0.2 m west of the block.
    for y in 0..200 {
        map.set(80, y, LETHAL);
    }
    let config = MissionConfig::default();
    let (centre, read) = (Point2::new(1.0, 1.0), Some(Point2::new(0.2, 1.0)));
    let p = staging_point(centre, read, Point2::new(1.8, 1.0), &map, &config);
    assert!(p.x > 0.82, "clear of the wall: {p:?}");
    // 30 degrees off west still ends 0.26 m out, behind the wall; 60 degrees does not.
    let bearing = (p.y - 1.0).atan2(p.x - 1.0).to_degrees().abs();
    assert!((bearing - 120.0).abs() < 1e-6, "{bearing}");
}

/// The robot 0.25 m south of a block mapped 9.5 cm west of where its markers, read with
/// it at `at`, put it (its south face mapped), facing it, in the last of its approach.
struct Scene {
    map: Costmap,
    occupied: Vec<bool>,
    pose: crate::geometry::Pose2,
    pick: Pickup,
    objects: Objects,
    truth: Point2,
}

fn scene(at: Point2) -> Scene {
    let map = Costmap::new(200, 200, 0.01, Point2::new(0.0, 0.0), FREE);
    let mut objects = Objects::default();
    see(&mut objects, at, &map);
    let block = *objects.blocks().next().unwrap();
    let truth = Point2::new(block.position.x - 0.095, block.position.y);
    let mut occupied = vec![false; 200 * 200];
    for i in 0..=5 {
        let at = Point2::new(truth.x - 0.025 + i as f64 * 0.01, truth.y - 0.025);
        let (cx, cy) = map.cell_of(at).unwrap();
        occupied[map.index(cx, cy)] = true;
    }
    let pose = crate::geometry::Pose2::new(truth.x, truth.y - 0.25, std::f64::consts::FRAC_PI_2);
    let config = MissionConfig::default();
    let mut pick = Pickup::new(&block, None, pose.position(), &map, &config, 0.0);
    pick.enter(Stage::Approach(Pace::new()), 0.0);
    Scene {
        map,
        occupied,
        pose,
        pick,
        objects,
        truth,
    }
}

/// The block's two markers read as if it were centred at `at`.
fn see(objects: &mut Objects, at: Point2, map: &Costmap) {
    let landmarks = [
        (421, Point2::new(at.x + 0.025, at.y)),
        (422, Point2::new(at.x, at.y + 0.025)),
    ];
    let robot = Point2::new(at.x, at.y - 0.5);
    objects.update(&landmarks.into_iter().collect(), robot, 0.05, map);
}

/// One approach step at `t`: how fast the robot turns.
fn turn_rate(s: &mut Scene, t: f64) -> f64 {
    let inputs = Inputs {
        gripper: Some(GripperState::Open),
        ..Inputs::quiet(t, s.pose, &s.map, &s.occupied)
    };
    let (mut ctx, mut log) = (Ctx::default(), Vec::new());
    let config = MissionConfig::default();
    match s
        .pick
        .step(&inputs, &config, &s.objects, &mut ctx, None, &mut log)
    {
        PickEvent::Go(Motion::Drive(tw), None) => tw.angular,
        other => panic!("{other:?}"),
    }
}

#[test]
fn the_approach_keeps_the_mapped_outline_when_the_markers_estimate_drifts_off_it() {
    // The markers put the block 9.5 cm east of where the lidar mapped it: the outline is
    // found and aimed at, straight ahead.
    let mut s = scene(Point2::new(1.0, 1.0));
    assert!(turn_rate(&mut s, 0.0).abs() < 0.02);
    // Then over 10 cm east, beyond the 10 cm searched round it: the approach still aims at
    // the outline rather than turning its jaws 20° and more towards the estimate, into
    // the block.
    see(&mut s.objects, Point2::new(1.012, 1.0), &s.map);
    let moved = s.objects.blocks().next().unwrap().position;
    assert!(moved.distance(s.truth) > 0.105, "{moved:?}");
    assert!(turn_rate(&mut s, 0.1).abs() < 0.02);
}
