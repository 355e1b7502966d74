use super::*;
use crate::data::GripperCommand;
use crate::data::robot::RobotConfig;
use crate::geometry::Twist;
use crate::sim::config::SimConfig;

fn open_room() -> World {
    let mut world = World::default_arena();
    world.walls.retain(|w| {
        // Only the outer boundary: keep segments on the arena's edge.
        let edge = |p: Point2| p.x.abs() > 1.99 || p.y.abs() > 1.99;
        edge(w.a) && edge(w.b)
    });
    world.obstacles.clear();
    world.blocks.truncate(1);
    world.blocks[0].pose = Pose2::new(1.0, -1.0, 0.0);
    world.start = Pose2::new(-1.0, 0.0, 0.0);
    world
}

fn twin_at(world: &World, pose: Pose2, seed: u64) -> Twin {
    let mut w = world.clone();
    w.start = pose;
    Twin::new(w, &RobotConfig::default(), &SimConfig::default(), seed)
}

/// Steps every twin `seconds` in 0.05 s turns, through the board.
fn run(board: &mut FleetBoard, twins: &mut [Twin], seconds: f64) {
    for _ in 0..(seconds / 0.05).round() as usize {
        for (i, twin) in twins.iter_mut().enumerate() {
            board.before_step(i, twin);
            twin.step(0.05);
            board.after_step(i, twin);
        }
    }
}

#[test]
fn spread_starts_begin_at_the_worlds_start_and_keep_clear_of_everything() {
    let world = World::default_arena();
    let r = RobotConfig::default().footprint_radius;
    let starts = spread_starts(&world, 8, r).unwrap();
    assert_eq!(starts.len(), 8);
    assert_eq!(starts[0], world.start);
    for (i, a) in starts.iter().enumerate() {
        assert_eq!(a.theta, world.start.theta);
        for w in &world.walls {
            assert!(dist2_to_segment(a.position(), w.a, w.b).sqrt() >= r + START_CLEARANCE);
        }
        for b in &starts[i + 1..] {
            assert!(a.position().distance(b.position()) >= 2.0 * r + START_GAP - 1e-9);
        }
    }
    let err = spread_starts(&world, 400, r).unwrap_err();
    assert!(err.contains("not 400") && err.contains("arena"), "{err}");
}

#[test]
fn a_robot_driving_at_another_stops_against_it_and_its_lidar_sees_it() {
    let world = open_room();
    let starts = [Pose2::new(-1.0, 0.0, 0.0), Pose2::new(-0.4, 0.0, 0.0)];
    let r = RobotConfig::default().footprint_radius;
    let mut board = FleetBoard::new(&world, &starts, r);
    let mut twins: Vec<Twin> = (starts.iter().enumerate())
        .map(|(i, &s)| twin_at(&world, s, i as u64))
        .collect();
    run(&mut board, &mut twins, 0.5);
    let scan = twins[0].take_frame().scan.expect("a scan");
    // The beam straight ahead ends on the other robot's near side, not the far wall.
    let ahead = scan
        .ranges
        .iter()
        .enumerate()
        .min_by_key(|(k, _)| {
            let a = scan.angle_min + *k as f64 * scan.angle_increment;
            (crate::geometry::wrap_angle(a).abs() * 1e6) as i64
        })
        .map(|(_, r)| *r as f64)
        .unwrap();
    assert!((ahead - (0.6 - r)).abs() < 0.03, "ahead {ahead}");
    twins[0].set_command(Twist::new(0.2, 0.0));
    run(&mut board, &mut twins, 5.0);
    let gap = twins[0]
        .pose()
        .position()
        .distance(twins[1].pose().position());
    assert!(gap >= 2.0 * r - 1e-6 && gap < 2.0 * r + 0.02, "gap {gap}");
    assert_eq!((twins[0].robot_hits(), twins[0].collisions()), (1, 1));
    assert_eq!(twins[1].collisions(), 0);
    // Without the board the same drive runs through where the other robot stands.
    let mut alone = twin_at(&world, starts[0], 0);
    alone.set_command(Twist::new(0.2, 0.0));
    alone.step(5.0);
    assert!(alone.pose().x > -0.2 && alone.collisions() == 0);
}

#[test]
fn a_block_one_robot_carries_is_gone_for_the_others_until_it_lets_go() {
    let world = open_room();
    let block = world.blocks[0].pose;
    // Robot 0 stands with the block in its jaws' zone; robot 1 across the room.
    let starts = [
        Pose2::new(block.x - 0.10, block.y, 0.0),
        Pose2::new(-1.0, 1.0, 0.0),
    ];
    let r = RobotConfig::default().footprint_radius;
    let mut board = FleetBoard::new(&world, &starts, r);
    let mut twins: Vec<Twin> = (starts.iter().enumerate())
        .map(|(i, &s)| twin_at(&world, s, i as u64))
        .collect();
    twins[0].command_gripper(GripperCommand::Open);
    run(&mut board, &mut twins, 1.5);
    twins[0].command_gripper(GripperCommand::Close);
    run(&mut board, &mut twins, 1.5);
    assert_eq!(twins[0].held_block(), Some(0));
    assert!(
        twins[1].blocks()[0].held,
        "robot 1 still sees the carried block"
    );
    // Carried 0.5 m up and let go: robot 1 finds it there.
    twins[0].set_command(Twist::new(0.0, 1.0));
    run(&mut board, &mut twins, std::f64::consts::FRAC_PI_2);
    twins[0].set_command(Twist::new(0.2, 0.0));
    run(&mut board, &mut twins, 2.5);
    twins[0].set_command(Twist::ZERO);
    twins[0].command_gripper(GripperCommand::Open);
    run(&mut board, &mut twins, 0.5);
    let (here, there) = (&twins[0].blocks()[0], &twins[1].blocks()[0]);
    assert!(!here.held && !there.held);
    assert_eq!(here.pose, there.pose);
    assert!(there.pose.y > block.y + 0.4, "{:?}", there.pose);
}
