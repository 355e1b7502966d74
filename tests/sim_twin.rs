//! The twin as a user of it notices it: driving, odometry, sensors, collisions, gripper,
//! step-size independence and determinism.

use navdeck::config::Config;
use navdeck::data::{GripperCommand, GripperState, LaserScan, SensorFrame};
use navdeck::geometry::{Pose2, Twist};
use navdeck::sim::{Twin, World};
use std::f64::consts::PI;
use std::path::Path;

/// A twin in `world` with `config`'s robot and sensors.
fn twin_in(world: World, config: &Config, seed: u64) -> Twin {
    Twin::new(world, &config.robot, &config.sim, seed)
}

/// An empty 4 m x 4 m arena plus `extra` world-file text, robot at `start` (degrees).
fn world(start: [f64; 3], extra: &str) -> World {
    let text = format!(
        "name = \"test\"\nsize = [4.0, 4.0]\nstart = [{}, {}, {}]\n\
         [[walls]]\npoints = [[-2.0, -2.0], [2.0, -2.0], [2.0, 2.0], [-2.0, 2.0]]\nclosed = true\n{extra}",
        start[0], start[1], start[2]
    );
    World::from_toml(&text, Path::new("test.toml")).unwrap()
}

/// Seed 001's robot with every source of noise turned off.
fn quiet() -> Config {
    let mut c = Config::default();
    c.sim.encoders.noise_std = 0.0;
    c.sim.encoders.slip_probability = 0.0;
    c.sim.camera.dist_std = 0.0;
    c.sim.camera.angle_std_deg = 0.0;
    c.sim.camera.miss_probability = 0.0;
    c.sim.lidar.range_std = 0.0;
    c
}

fn drive(twin: &mut Twin, twist: Twist, seconds: f64) {
    twin.set_command(twist);
    twin.step(seconds);
}

#[test]
fn twin_is_clone_and_send() {
    fn needs<T: Clone + Send>() {}
    needs::<Twin>();
}

#[test]
fn driving_straight_one_second_at_a_tenth_moves_a_tenth() {
    let mut t = twin_in(world([0.0, 0.0, 30.0], ""), &quiet(), 1);
    drive(&mut t, Twist::new(0.1, 0.0), 1.0);
    let p = t.pose();
    // 0.1 m less the 5 mm lost to the 0.1 s ramp at 1 m/s^2.
    let along = p.x * 30f64.to_radians().cos() + p.y * 30f64.to_radians().sin();
    assert!((along - 0.095).abs() < 1e-9, "{p:?}");
    assert!((p.theta - 30f64.to_radians()).abs() < 1e-12);
    assert!((t.distance_driven() - 0.095).abs() < 1e-9);
    assert!((t.time() - 1.0).abs() < 1e-12);
}

#[test]
fn spinning_in_place_keeps_the_position() {
    let mut t = twin_in(world([0.3, -0.2, 0.0], ""), &quiet(), 1);
    drive(&mut t, Twist::new(0.0, 2.0), 2.0);
    let p = t.pose();
    assert!(
        (p.x - 0.3).abs() < 1e-12 && (p.y + 0.2).abs() < 1e-12,
        "{p:?}"
    );
    // 2 rad/s for 2 s less the 0.125 s ramp at 8 rad/s^2: 4 - 0.25 = 3.75 rad.
    assert!((p.theta - (3.75 - 2.0 * PI)).abs() < 1e-9, "{p:?}");
    assert_eq!(t.distance_driven(), 0.0);
}

#[test]
fn acceleration_limit_shapes_the_ramp_and_speed_is_capped() {
    let mut t = twin_in(world([-1.5, 0.0, 0.0], ""), &quiet(), 1);
    t.set_command(Twist::new(2.0, 0.0));
    let mut speeds = Vec::new();
    for _ in 0..6 {
        t.step(0.1);
        speeds.push(t.velocity().linear);
    }
    let want = [0.1, 0.2, 0.3, 0.4, 0.4, 0.4];
    for (got, want) in speeds.iter().zip(want) {
        assert!((got - want).abs() < 1e-9, "{speeds:?}");
    }
    // 0.08 m while ramping for 0.4 s, then 0.4 m/s for 0.2 s.
    assert!((t.pose().x + 1.5 - 0.16).abs() < 1e-9, "{:?}", t.pose());
}

#[test]
fn encoder_travel_agrees_with_true_travel_within_noise() {
    let mut t = twin_in(World::default_arena(), &Config::default(), 11);
    t.set_command(Twist::new(0.2, 0.4));
    let (mut odo, mut turn) = (0.0, 0.0);
    for _ in 0..100 {
        t.step(0.1);
        let w = t.take_frame().wheels.unwrap();
        odo += (w.left + w.right) / 2.0;
        turn += (w.right - w.left) / Config::default().robot.track;
    }
    let truth = t.distance_driven();
    assert_eq!(t.collisions(), 0);
    assert!(truth > 1.8, "{truth}");
    assert!(odo != truth, "the default config has encoder noise");
    assert!(
        (odo - truth).abs() < 0.01 * truth,
        "odometry {odo} vs truth {truth}"
    );
    // About 3.9 rad of turning: odometry agrees on the heading within a few degrees.
    let heading = navdeck::geometry::wrap_angle(t.pose().theta - turn);
    assert!(heading.abs() < 0.1, "heading error {heading}");
}

fn scripted(twin: &mut Twin, slices: &[f64]) -> SensorFrame {
    twin.set_command(Twist::new(0.25, 0.6));
    twin.command_gripper(GripperCommand::Open);
    for &dt in slices {
        twin.step(dt);
    }
    twin.take_frame()
}

#[test]
fn one_long_step_equals_many_short_ones() {
    let make = || twin_in(World::default_arena(), &Config::default(), 5);
    let (mut a, mut b, mut c) = (make(), make(), make());
    let fa = scripted(&mut a, &[1.0]);
    let fb = scripted(&mut b, &[0.1; 10]);
    let fc = scripted(&mut c, &[0.003; 334]);
    assert_eq!(a.pose(), b.pose());
    assert_eq!(fa, fb);
    // 334 x 3 ms = 1.002 s: the same 100 physics steps and 2 ms carried over.
    assert!(
        (a.pose().x - c.pose().x).abs() < 1e-12 && (a.pose().theta - c.pose().theta).abs() < 1e-12
    );
    assert_eq!(fa.wheels, fc.wheels);
    assert_eq!(a.gripper(), GripperState::Open);
    // The carried 2 ms is not lost: 8 ms more completes another physics step.
    c.step(0.008);
    assert!((c.time() - 1.01).abs() < 1e-12, "{}", c.time());
}

#[test]
fn zero_and_tiny_steps_accumulate() {
    let mut t = twin_in(world([0.0, 0.0, 0.0], ""), &quiet(), 1);
    t.set_command(Twist::new(0.1, 0.0));
    t.step(0.0);
    t.step(-1.0);
    t.step(f64::NAN);
    assert_eq!(t.time(), 0.0);
    for _ in 0..1000 {
        t.step(0.0001);
    }
    assert!((t.time() - 0.1).abs() < 1e-12);
    assert!(t.pose().x > 0.0);
}

#[test]
fn same_seed_same_frames_and_different_seeds_differ() {
    let run = |seed: u64| {
        let mut t = twin_in(World::default_arena(), &Config::default(), seed);
        t.set_command(Twist::new(0.15, 0.3));
        (0..30)
            .map(|_| {
                t.step(0.1);
                t.take_frame()
            })
            .collect::<Vec<_>>()
    };
    let (a, b, c) = (run(42), run(42), run(43));
    assert_eq!(a, b);
    assert_ne!(a, c);
    assert!(
        a.iter()
            .any(|f| f.sightings.as_ref().is_some_and(|s| !s.is_empty()))
    );
    assert_eq!(
        a.iter().filter(|f| f.scan.is_some()).count(),
        15,
        "lidar at 5 Hz"
    );
    assert_eq!(
        a.iter().filter(|f| f.sightings.is_some()).count(),
        30,
        "camera at 10 Hz"
    );
}

#[test]
fn frames_carry_the_newest_camera_frame_once() {
    let mut t = twin_in(World::default_arena(), &quiet(), 1);
    t.step(0.05);
    let f = t.take_frame();
    assert!(
        f.sightings.is_none() && f.scan.is_none(),
        "no camera frame in the first 50 ms"
    );
    assert_eq!(f.gripper, Some(GripperState::Closed));
    assert!((f.elapsed - 0.05).abs() < 1e-12);
    t.step(0.2);
    let f = t.take_frame();
    assert!(f.sightings.is_some() && f.scan.is_some());
    assert!(t.take_frame().sightings.is_none(), "taken once");
}

#[test]
fn camera_reports_a_marker_ahead_and_not_one_hidden_behind_an_obstacle() {
    let extra = "[[markers]]\nid = 200\nx = 1.0\ny = 0.0\nfacing_deg = 180.0\n\
                 [[markers]]\nid = 201\nx = 0.0\ny = 1.5\nfacing_deg = -90.0\n";
    let mut t = twin_in(world([0.0, 0.0, 0.0], extra), &quiet(), 1);
    t.step(0.1);
    let seen = t.take_frame().sightings.unwrap();
    assert_eq!(seen.len(), 1, "{seen:?}");
    assert_eq!(seen[0].id, 200);
    assert!((seen[0].range - 1.0).abs() < 1e-12 && seen[0].bearing.abs() < 1e-12);
    // A quarter turn left: 201 straight ahead at 1.5 m, 200 now out of view.
    drive(&mut t, Twist::new(0.0, PI / 2.0), 1.1);
    drive(&mut t, Twist::ZERO, 0.5);
    let turned = t.pose().theta;
    let seen = t.take_frame().sightings.unwrap();
    assert_eq!(seen.iter().map(|s| s.id).collect::<Vec<_>>(), vec![201]);
    assert!((seen[0].bearing - (PI / 2.0 - turned)).abs() < 1e-9);

    let hidden = format!("{extra}[[obstacles]]\ncenter = [0.5, 0.0]\nsize = [0.1, 0.3]\n");
    let mut t = twin_in(world([0.0, 0.0, 0.0], &hidden), &quiet(), 1);
    t.step(0.1);
    assert_eq!(t.take_frame().sightings.unwrap(), vec![]);
}

#[test]
fn camera_sees_block_markers_where_the_block_is() {
    let extra =
        "[[blocks]]\ncolor = \"red\"\nx = 0.5\ny = 0.5\nyaw_deg = 180.0\nmarkers = [421, 422]\n";
    let mut t = twin_in(world([0.0, 0.0, 45.0], extra), &quiet(), 1);
    t.step(0.1);
    let mut ids: Vec<u32> = t
        .take_frame()
        .sightings
        .unwrap()
        .iter()
        .map(|s| s.id)
        .collect();
    ids.sort();
    assert_eq!(ids, vec![421, 422], "both faces show from the diagonal");
}

/// The range of `scan`'s beam nearest `deg` degrees from the robot's heading.
fn range_at(scan: &LaserScan, deg: f64) -> f32 {
    scan.ranges[((deg.to_radians() - scan.angle_min) / scan.angle_increment).round() as usize]
}

#[test]
fn lidar_reads_the_arena_walls_and_obstacles() {
    let mut t = twin_in(world([0.0, 0.0, 0.0], ""), &quiet(), 1);
    t.step(0.2);
    let scan = t.take_frame().scan.unwrap();
    assert_eq!(scan.ranges.len(), 360);
    assert_eq!(scan.angle_min, -PI);
    assert!((range_at(&scan, 0.0) - 2.0).abs() < 1e-6);
    assert!((range_at(&scan, 90.0) - 2.0).abs() < 1e-6);
    assert!((range_at(&scan, -90.0) - 2.0).abs() < 1e-6);
    assert!((range_at(&scan, 45.0) - 8f32.sqrt()).abs() < 1e-5);

    let boxed = "[[obstacles]]\ncenter = [0.0, -1.0]\nsize = [0.4, 0.2]\n";
    let mut t = twin_in(world([0.0, 0.0, 0.0], boxed), &quiet(), 1);
    t.step(0.2);
    let near = t.take_frame().scan.unwrap();
    assert!(
        (range_at(&near, -90.0) - 0.9).abs() < 1e-6,
        "the box face at y = -0.9"
    );
    assert!((range_at(&near, -100.0) - 0.9 / 80f32.to_radians().sin()).abs() < 1e-5);
    assert_eq!(
        range_at(&near, 0.0),
        range_at(&scan, 0.0),
        "beams away from the box unchanged"
    );
    assert_eq!(range_at(&near, -70.0), range_at(&scan, -70.0));
}

#[test]
fn driving_into_a_wall_stops_once_and_backing_off_works() {
    let mut t = twin_in(world([1.5, 0.3, 0.0], ""), &quiet(), 1);
    drive(&mut t, Twist::new(0.3, 0.0), 3.0);
    let r = Config::default().robot.footprint_radius;
    let stopped = t.pose().x;
    assert!(
        stopped + r <= 2.0 && stopped + r > 1.99,
        "stopped at {stopped}"
    );
    assert_eq!(t.collisions(), 1);
    assert!(t.velocity().is_zero() || t.velocity().linear < 0.05);
    drive(&mut t, Twist::new(0.3, 0.0), 2.0);
    assert_eq!(t.collisions(), 1, "pushing on is the same contact");
    assert!(t.pose().x + r <= 2.0);
    let odometer = t.take_frame().wheels.unwrap();
    assert!(
        odometer.left < (stopped - 1.5) + 0.01,
        "encoders do not run while blocked"
    );
    drive(&mut t, Twist::new(-0.2, 0.0), 1.0);
    assert!(t.pose().x < stopped - 0.15, "{:?}", t.pose());
    drive(&mut t, Twist::new(0.3, 0.0), 2.0);
    assert_eq!(t.collisions(), 2, "a new contact counts again");
}

#[test]
fn gripper_catches_a_block_in_its_jaws_and_carries_it() {
    let extra = "[[blocks]]\ncolor = \"blue\"\nx = 0.3\ny = 0.0\nmarkers = [521, 522]\n";
    let mut t = twin_in(world([0.0, 0.0, 0.0], extra), &quiet(), 1);
    t.command_gripper(GripperCommand::Open);
    t.step(1.0);
    assert_eq!(t.gripper(), GripperState::Open);
    // Drive until the block sits in the open jaws (0.06-0.14 m ahead).
    drive(&mut t, Twist::new(0.1, 0.0), 1.8);
    drive(&mut t, Twist::ZERO, 0.2);
    assert_eq!(t.collisions(), 0, "an open gripper lets the block in");
    t.command_gripper(GripperCommand::Close);
    t.step(0.5);
    assert_eq!(t.gripper(), GripperState::Closing);
    t.step(0.6);
    assert_eq!(t.gripper(), GripperState::Holding);
    assert!(t.blocks()[0].held);
    let before = t
        .pose()
        .inverse_transform_point(t.blocks()[0].pose.position());
    drive(&mut t, Twist::new(0.15, 0.8), 2.0);
    let after = t
        .pose()
        .inverse_transform_point(t.blocks()[0].pose.position());
    assert!(
        t.blocks()[0]
            .pose
            .position()
            .distance(navdeck::geometry::Point2::new(0.3, 0.0))
            > 0.2
    );
    assert!(before.distance(after) < 1e-9, "the block rides in the jaws");
    // Opening lets go where it is; backing away leaves it behind.
    drive(&mut t, Twist::ZERO, 0.5);
    t.command_gripper(GripperCommand::Open);
    let dropped = t.blocks()[0].pose;
    drive(&mut t, Twist::new(-0.1, 0.0), 1.5);
    assert!(!t.blocks()[0].held);
    assert_eq!(t.blocks()[0].pose, dropped);
    assert_eq!(t.collisions(), 0);
}

#[test]
fn closing_on_nothing_ends_closed_and_a_closed_gripper_bumps_blocks() {
    let extra = "[[blocks]]\ncolor = \"red\"\nx = 0.5\ny = 0.0\nmarkers = [423, 424]\n";
    let mut t = twin_in(world([0.0, 0.0, 0.0], extra), &quiet(), 1);
    t.command_gripper(GripperCommand::Open);
    t.step(1.0);
    t.command_gripper(GripperCommand::Close);
    t.step(1.0);
    assert_eq!(t.gripper(), GripperState::Closed);
    drive(&mut t, Twist::new(0.2, 0.0), 3.0);
    assert_eq!(t.collisions(), 1);
    let gap = t.pose().position().distance(t.blocks()[0].pose.position());
    assert!(gap >= 0.08 + 0.05 / 2f64.sqrt() - 1e-9, "{gap}");
    assert_eq!(
        t.blocks()[0].pose,
        Pose2::new(0.5, 0.0, 0.0),
        "a bumped block stays put"
    );
}

#[test]
fn lidar_sees_free_blocks_but_not_the_held_one() {
    let extra = "[[blocks]]\ncolor = \"red\"\nx = 0.1\ny = 0.0\nmarkers = [421, 422]\n\
                 [[blocks]]\ncolor = \"red\"\nx = 0.0\ny = 1.0\nsize = 0.1\nmarkers = [423, 424]\n";
    let mut t = twin_in(world([0.0, 0.0, 0.0], extra), &quiet(), 1);
    t.command_gripper(GripperCommand::Open);
    t.step(1.0);
    t.command_gripper(GripperCommand::Close);
    t.step(1.0);
    assert_eq!(t.gripper(), GripperState::Holding);
    t.step(0.2);
    let scan = t.take_frame().scan.unwrap();
    assert!(
        (range_at(&scan, 90.0) - 0.95).abs() < 1e-6,
        "free block's face"
    );
    assert!(
        (range_at(&scan, 0.0) - 2.0).abs() < 1e-6,
        "the held block is not seen"
    );
}

#[test]
fn the_warehouse_world_drives_and_shows_markers() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("maps/warehouse.toml");
    let mut t = twin_in(World::load(&path).unwrap(), &quiet(), 3);
    let mut seen = std::collections::BTreeSet::new();
    t.set_command(Twist::new(0.2, 0.0));
    for _ in 0..40 {
        t.step(0.1);
        seen.extend(
            t.take_frame()
                .sightings
                .unwrap_or_default()
                .iter()
                .map(|s| s.id),
        );
    }
    assert_eq!(t.collisions(), 0);
    assert!(t.pose().y > -2.5 + 0.7, "{:?}", t.pose());
    // Heading north up the west aisle: the pallet ahead and the west wall show up.
    assert!(seen.iter().any(|id| (301..=304).contains(id)), "{seen:?}");
    assert!(seen.iter().any(|id| *id <= 56), "{seen:?}");
}

/// A door jamb seen end-on, from the doorway it bounds, still shows on the lidar: world
/// walls are lines, and a real wall's end has a face. The boundary's corners do not grow.
#[test]
fn lidar_sees_a_door_jamb_end_on() {
    // A wall from (0, 0.5) up to the north boundary; the robot stands on its line, south.
    let jamb = "[[walls]]\npoints = [[0.0, 0.5], [0.0, 2.0]]\n";
    let mut t = twin_in(world([0.0, -0.5, 0.0], jamb), &quiet(), 1);
    t.step(0.2);
    let scan = t.take_frame().scan.unwrap();
    assert!(
        (range_at(&scan, 90.0) - 1.0).abs() < 1e-6,
        "the jamb's end 1 m north, read {}",
        range_at(&scan, 90.0)
    );
    let faces = World::from_toml(
        &std::fs::read_to_string("maps/arena.toml").unwrap(),
        Path::new("maps/arena.toml"),
    )
    .unwrap()
    .wall_end_faces(0.025);
    assert!(
        faces.is_empty(),
        "closed walls have no free ends: {faces:?}"
    );
}
