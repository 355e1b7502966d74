//! Route mode (seed 003) in the pilot, through the runtime the console uses: the twin's
//! floor carries the tag warehouse, its ideal tag camera's sightings cross the link in
//! each frame, and the pilot drives a task to the dock, resets its pose at every tag,
//! marks an edge the collision monitor holds it on as blocked and goes round it. Time
//! comes from a `ManualClock`, a control period at a time.

use navdeck::config::Config;
use navdeck::geometry::{Point2, Pose2};
use navdeck::link::runtime::Runtime;
use navdeck::link::sim::SimLink;
use navdeck::pilot::Intent;
use navdeck::pilot::behaviours::Behaviour;
use navdeck::pilot::mode::Mode;
use navdeck::pilot::tag_route::TagGoal;
use navdeck::pilot::teleop::DriveKey;
use navdeck::sim::Twin;
use navdeck::sim::tag_camera::TagCamera;
use navdeck::tags::drive::{DriveGains, DriveSetup, Phase};
use navdeck::tags::{TagId, TagMap};
use navdeck::tui::events::{Clock, ManualClock};
use std::sync::Arc;

fn warehouse() -> TagMap {
    TagMap::parse(include_str!("../maps/tag_warehouse.yaml")).unwrap()
}

/// The twin on `map`'s floor (boxes on `obstacles`), the robot on the dock, and a
/// runtime whose pilot knows the map.
fn rig_on(map: TagMap, obstacles: &[(TagId, TagId)]) -> Rig {
    let config = Config::default();
    let map = Arc::new(map);
    let camera = TagCamera::default();
    let world = navdeck::tags::floor::world_for(&map, camera.look, obstacles).unwrap();
    let mut twin = Twin::new(world, &config.robot, &config.sim, 3);
    twin.use_tag_camera(map.clone(), camera, 3);
    let mut runtime = Runtime::new(
        Box::new(SimLink::new(twin, 0.0)),
        config.pilot_settings(),
        0.0,
    );
    let setup = DriveSetup {
        gains: DriveGains::from_map(&map),
        look: camera.look,
        ..DriveSetup::default()
    };
    runtime.pilot_mut().set_tag_map(Some(map), setup);
    Rig::new(runtime)
}

fn rig(obstacles: &[(TagId, TagId)]) -> (Rig, Arc<TagMap>) {
    let robot = rig_on(warehouse(), obstacles);
    let map = Arc::new(warehouse());
    (robot, map)
}

/// Asks for `goal` at the start, as `:route` does.
fn go(robot: &mut Rig, goal: TagGoal) {
    robot.tick(0.0);
    robot.intend(Intent::TagRoute(goal));
}

fn truth(rig: &Rig) -> Pose2 {
    rig.robot.link().ground_truth().unwrap().pose()
}

fn collisions(rig: &Rig) -> u32 {
    rig.robot.link().ground_truth().unwrap().collisions()
}

/// The runtime and every log line its steps gave.
struct Rig {
    robot: Runtime,
    log: Vec<String>,
}

impl Rig {
    fn new(robot: Runtime) -> Self {
        Self {
            robot,
            log: Vec::new(),
        }
    }

    fn keep(&mut self, stepped: navdeck::link::runtime::Stepped) {
        let lines = stepped.log_lines().map(|(_, _, l)| l.to_string());
        self.log.extend(lines);
    }

    fn tick(&mut self, t: f64) {
        let stepped = self.robot.tick(t, Vec::new());
        self.keep(stepped);
    }

    fn intend(&mut self, intent: Intent) {
        let stepped = self.robot.intend(intent);
        self.keep(stepped);
    }

    fn pilot(&self) -> &navdeck::pilot::Pilot {
        self.robot.pilot()
    }

    fn logged(&self, text: &str) -> bool {
        self.log.iter().any(|line| line.contains(text))
    }

    fn log_text(&self) -> String {
        self.log.join("\n")
    }
}

/// Control periods on `clock` until `done` or `seconds` pass.
fn run_until(rig: &mut Rig, clock: &ManualClock, seconds: f64, done: impl Fn(&Rig) -> bool) {
    let period = rig.pilot().settings().robot.control_period;
    let end = clock.now() + seconds;
    while clock.now() < end && !done(rig) {
        clock.advance(period);
        rig.tick(clock.now());
    }
}

fn ended(rig: &Rig) -> bool {
    let run = rig.pilot().tag_route().run();
    run.is_some_and(|r| matches!(r.phase(), Phase::Done | Phase::Failed))
}

#[test]
fn a_warehouse_task_is_driven_to_the_dock_and_the_estimate_ends_within_5_cm_of_the_truth() {
    let (mut robot, map) = rig(&[]);
    let clock = ManualClock::default();
    go(&mut robot, TagGoal::Task("task1".into()));
    assert_eq!(robot.pilot().mode(), Mode::Route);
    run_until(&mut robot, &clock, 300.0, ended);
    let routing = robot.pilot().tag_route();
    let run = routing.run().expect("a run");
    assert_eq!(run.phase(), Phase::Done, "{}", robot.log_text());
    assert_eq!(run.route().tags.first(), Some(&508));
    assert_eq!(run.route().tags.last(), Some(&508));
    assert!(robot.logged("route: task task1 done, on tag 508"));
    // The route's tags reset the pose the console shows: at the dock it is the truth's.
    let (est, real) = (robot.pilot().estimated_pose(), truth(&robot));
    let off = est.position().distance(real.position());
    assert!(
        off < 0.05,
        "estimate {est:?} is {off:.3} m from the truth {real:?}"
    );
    assert!(routing.resets() > 10, "{} resets", routing.resets());
    assert_eq!(routing.last_reset().map(|r| r.tag), Some(508));
    // And the robot stands on the dock: its camera's floor point within 5 cm of it.
    let dock = &map.tags[&508];
    let centre = TagCamera::default().centre(real);
    let from_dock = centre.distance(Point2::new(dock.x, dock.y));
    assert!(from_dock < 0.05, "{from_dock:.3} m from the dock tag");
    assert_eq!(robot.pilot().commanded().linear, 0.0);
    assert_eq!(collisions(&robot), 0);
}

/// A generated grid with a box on an edge one of its tasks drives first: the grid, the
/// task and the boxed edge (as the route drives it).
fn boxed_grid() -> (TagMap, String, (TagId, TagId)) {
    for seed in 1..60 {
        let grid = navdeck::tags::generate::grid(seed);
        for name in grid.map.tasks.keys() {
            let Some(Ok(route)) = grid.map.task_route(name, &Default::default()) else {
                continue;
            };
            for leg in &route.legs {
                let on = |&(a, b): &(TagId, TagId)| {
                    (a, b) == (leg.from, leg.to) || (b, a) == (leg.from, leg.to)
                };
                if grid.obstacles.iter().any(on) {
                    return (grid.map.clone(), name.clone(), (leg.from, leg.to));
                }
            }
        }
    }
    panic!("no generated grid with a box on a task's route");
}

#[test]
fn an_edge_the_collision_monitor_holds_the_robot_on_is_marked_blocked_and_driven_round() {
    let (map, task, boxed) = boxed_grid();
    let mut robot = rig_on(map, &[boxed]);
    let clock = ManualClock::default();
    go(&mut robot, TagGoal::Task(task));
    let blocked =
        |r: &Rig| (r.pilot().tag_route().run()).is_some_and(|run| !run.blocked_edges().is_empty());
    run_until(&mut robot, &clock, 300.0, blocked);
    assert!(blocked(&robot), "{}", robot.log_text());
    let run = robot.pilot().tag_route().run().unwrap();
    assert_eq!(run.blocked_edges(), [boxed]);
    let said = format!(
        "({} → {}) blocked (the collision monitor held the robot 2 s)",
        boxed.0, boxed.1
    );
    assert!(robot.logged(&said), "{}", robot.log_text());
    // The monitor, above the route, held the robot clear of the box.
    let monitor = Some(Behaviour::CollisionMonitor);
    assert!(robot.pilot().arbiter().history().any(|tr| tr.to == monitor));
    run_until(&mut robot, &clock, 900.0, ended);
    let run = robot.pilot().tag_route().run().unwrap();
    assert_eq!(run.phase(), Phase::Done, "{}", robot.log_text());
    let driven = &run.route().tags;
    let crosses = |w: &[TagId]| w == [boxed.0, boxed.1] || w == [boxed.1, boxed.0];
    assert!(
        !driven.windows(2).skip(1).any(crosses),
        "the new route {driven:?} goes round {boxed:?}"
    );
    assert_eq!(collisions(&robot), 0);
}

#[test]
fn a_blocked_edge_with_no_way_round_fails_naming_the_leg_and_the_robot_stands() {
    // Zone A is one line of tags: a box between 102 and 103 leaves no way to the aisles.
    let (mut robot, _) = rig(&[(102, 103)]);
    let clock = ManualClock::default();
    go(&mut robot, TagGoal::Task("task1".into()));
    run_until(&mut robot, &clock, 120.0, |r| {
        r.pilot().tag_route().outcome().is_some()
    });
    let said = "route: leg 102-103 is blocked and there is no way round it";
    assert!(robot.logged(said), "{}", robot.log_text());
    run_until(&mut robot, &clock, 1.0, |_| false);
    assert_eq!(robot.pilot().commanded().linear, 0.0);
    assert_eq!(collisions(&robot), 0);
}

#[test]
fn stop_and_a_drive_key_take_over_and_route_mode_drives_on_from_where_it_stopped() {
    let (mut robot, _) = rig(&[]);
    let clock = ManualClock::default();
    robot.tick(0.0);
    robot.intend(Intent::TagRoute(TagGoal::Tag(120)));
    run_until(&mut robot, &clock, 5.0, |_| false);
    assert!(robot.pilot().commanded().linear > 0.1);
    robot.intend(Intent::Stop);
    assert_eq!(robot.pilot().mode(), Mode::Manual);
    assert!(robot.logged("stop: route paused, manual control (i drives the route on)"));
    run_until(&mut robot, &clock, 1.0, |_| false);
    assert_eq!(robot.pilot().commanded().linear, 0.0);
    // Back in route mode the run goes on from the tag nearest the robot.
    robot.intend(Intent::Mode(Mode::Route));
    assert!(robot.logged("route on: tag 120 by"), "{}", robot.log_text());
    let before = truth(&robot);
    run_until(&mut robot, &clock, 3.0, |_| false);
    let after = truth(&robot);
    let moved = after.position().distance(before.position());
    let turned = navdeck::geometry::wrap_angle(after.theta - before.theta).abs();
    assert!(moved > 0.1 || turned > 0.1, "{}", robot.log_text());
    // A drive key takes control back at once.
    robot.intend(Intent::KeyDown {
        key: DriveKey::TurnLeft,
        repeat: false,
    });
    assert_eq!(robot.pilot().mode(), Mode::Manual);
    assert_eq!(robot.pilot().commanded().linear, 0.0);
    // And the e-stop stops it from route mode too.
    robot.intend(Intent::Mode(Mode::Route));
    run_until(&mut robot, &clock, 2.0, |_| false);
    robot.intend(Intent::EmergencyStop);
    assert_eq!(robot.pilot().mode(), Mode::Manual);
    assert_eq!(robot.pilot().commanded().linear, 0.0);
}

#[test]
fn without_a_tag_map_route_mode_says_what_to_pass() {
    let config = Config::default();
    let twin = Twin::new(
        navdeck::sim::World::default_arena(),
        &config.robot,
        &config.sim,
        1,
    );
    let link = Box::new(SimLink::new(twin, 0.0));
    let mut robot = Rig::new(Runtime::new(link, config.pilot_settings(), 0.0));
    robot.tick(0.0);
    robot.intend(Intent::Mode(Mode::Route));
    assert_eq!(robot.pilot().mode(), Mode::Manual);
    assert!(robot.logged("route mode needs a tag map: start navdeck with --tags FILE"));
    robot.intend(Intent::TagRoute(TagGoal::Task("task1".into())));
    assert_eq!(robot.pilot().mode(), Mode::Manual);
}

#[test]
fn a_task_the_map_does_not_hold_and_a_robot_off_the_graph_are_named() {
    let (mut robot, _) = rig(&[]);
    robot.tick(0.0);
    robot.intend(Intent::TagRoute(TagGoal::Task("nowhere".into())));
    assert!(
        robot.logged("no task \"nowhere\" in the tag map (tasks: "),
        "{}",
        robot.log_text()
    );
    assert_eq!(robot.pilot().commanded().linear, 0.0);
    // Placed off the graph, the robot cannot start a route.
    let (mut lost, _) = rig(&[]);
    lost.tick(0.0);
    lost.intend(Intent::SetPose(Pose2::new(1.2, 1.0, 0.0)));
    lost.intend(Intent::TagRoute(TagGoal::Tag(120)));
    let said = "route mode starts on a tag; the nearest, tag 102, is 1.00 m away";
    assert!(lost.logged(said), "{}", lost.log_text());
}

#[test]
fn with_mcl_localising_a_tag_seen_gathers_its_particles_on_the_tag_pose() {
    let mut robot = rig_on(warehouse(), &[]);
    let clock = ManualClock::default();
    // MCL on the twin's own world, started 0.3 m and 10 degrees from the truth.
    let start = truth(&robot);
    let world =
        navdeck::tags::floor::world_for(&warehouse(), TagCamera::default().look, &[]).unwrap();
    let wrong = Pose2::new(
        start.x + 0.3,
        start.y - 0.1,
        start.theta + 10f64.to_radians(),
    );
    let initial = navdeck::pilot::localize::InitialPose::At(wrong);
    (robot
        .robot
        .pilot_mut()
        .use_mcl(&world.rasterize(0.05), initial, 7))
    .unwrap();
    let off = |rig: &Rig| {
        let (est, real) = (rig.pilot().estimated_pose(), truth(rig));
        est.position().distance(real.position())
    };
    assert!(off(&robot) > 0.25, "MCL starts wrong");
    // A period with the dock tag in view: the particles gather on the tag's pose.
    clock.advance(robot.pilot().settings().robot.control_period);
    robot.tick(clock.now());
    assert!(robot.pilot().mcl().is_some());
    assert_eq!(
        robot.pilot().tag_route().last_reset().map(|r| r.tag),
        Some(508)
    );
    assert!(
        off(&robot) < 0.02,
        "MCL's estimate {:.3} m off the truth",
        off(&robot)
    );
}
