//! `navdeck route`: a robot in the twin drives a tag map's task (seed 003) on simulated
//! time, seeing the floor's tags through the twin's ideal tag camera, with the wheel
//! odometry between tags and the collision monitor on the lidar. A leg the monitor
//! stops is marked blocked and the rest of the task planned again by BFS without it,
//! from the last tag reached. The run is scored against the truth: each tag's arrival,
//! each turn, and the end on the last tag (seed 003 §3.3: dock within 5 cm to the side,
//! turns within 5°). With `--sim-camera` (feature `vision`) the tags are seen in the
//! rendered camera's frames by OpenCV instead (`route_camera`).

use super::route_camera::{DetectionFigures, Eyes, TagSensor};
use crate::clock::Clock;
use crate::config::Config;
use crate::control::collision_monitor::{
    CollisionMonitor, Obstacles, SourceKind, points_from_scan,
};
use crate::geometry::{Pose2, Twist, wrap_angle};
use crate::sim::World;
use crate::sim::tag_camera::TagCamera;
use crate::slam::odometry::predict_pose;
use crate::tags::drive::{DriveEvent, DriveGains, DriveSetup, Phase, RouteRun};
use crate::tags::{TagId, TagMap};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

/// What a route run is asked to do.
#[derive(Clone, Debug)]
pub struct RouteOptions {
    pub task: String,
    pub seed: u64,
    /// Edges with a box standing on them, as (from, to).
    pub obstacles: Vec<(TagId, TagId)>,
    /// Simulated seconds after which the run ends unfinished.
    pub time_limit: f64,
    /// The control loop's period, seconds (seed 003 §2.4: 30 Hz).
    pub period: f64,
    /// The ideal tag camera, or the rendered one read by OpenCV (`--sim-camera`).
    pub sensor: TagSensor,
}

/// Where the robot stood, by the truth, when it reached a tag.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TagArrival {
    pub tag: TagId,
    /// Metres past (+) or short of the tag along the heading, and to its left (+).
    pub along_m: f64,
    pub side_m: f64,
}

/// The outcome of one route run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RouteReport {
    pub task: String,
    pub seed: u64,
    pub completed: bool,
    /// The tags of the route as first planned.
    pub planned: Vec<TagId>,
    /// Legs driven to their tag: one for each arrival.
    pub legs_driven: usize,
    pub arrivals: Vec<TagArrival>,
    /// Each turn's true heading error at its end, degrees.
    pub turn_errors_deg: Vec<f64>,
    /// On the last tag, by the truth: to its side, along, and the heading, against the
    /// tag's pose (the image centre over the tag, facing its zone's way).
    pub end_side_m: Option<f64>,
    pub end_along_m: Option<f64>,
    pub end_heading_deg: Option<f64>,
    /// Edges found blocked and routed round.
    pub blocked: Vec<(TagId, TagId)>,
    pub collisions: u32,
    pub failure: Option<String>,
    /// The tag sensor that ran, and with the rendered camera how it did.
    pub sensor: TagSensor,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub detection: Option<DetectionFigures>,
    pub sim_time: f64,
    pub wall_time_s: Option<f64>,
    pub realtime_factor: Option<f64>,
}

/// The control loop's rate by default (seed 003 §2.4, §3.3: 30 Hz).
pub const RATE_HZ: f64 = 30.0;

/// The twin's world for `map` (`tags::floor::world_for`), seen by `camera`.
pub fn world_for(
    map: &TagMap,
    camera: &TagCamera,
    obstacles: &[(TagId, TagId)],
) -> Result<World, String> {
    crate::tags::floor::world_for(map, camera.look, obstacles)
}

/// Runs `options.task` of `map` with `config`'s robot in the twin; `stopwatch` times the
/// rendered camera's frames.
pub fn run(
    config: &Config,
    map: &TagMap,
    options: &RouteOptions,
    stopwatch: Option<&dyn Clock>,
) -> Result<RouteReport, String> {
    let names: Vec<&str> = map.tasks.keys().map(String::as_str).collect();
    let task = (map.tasks.get(&options.task)).ok_or_else(|| {
        format!(
            "no task {:?} in the map (tasks: {})",
            options.task,
            names.join(", ")
        )
    })?;
    // The robot starts on the dock.
    let waypoints = RouteRun::task_waypoints(map.dock, task);
    // The tags' printed size: the map's `vision.tag_size`, else the camera's config.
    let tag_camera = &config.vision.tag_camera;
    let side = map.param_f64("vision.tag_size", tag_camera.tag_side);
    if !(0.005..=1.0).contains(&side) {
        return Err(format!(
            "the map's vision.tag_size = {side}: must lie in 0.005..=1 m"
        ));
    }
    let mut eyes = Eyes::new(options.sensor, map, tag_camera, side, options.seed)?;
    let camera = *eyes.ideal();
    let setup = DriveSetup {
        gains: DriveGains::from_map(map),
        look: camera.look,
        ..DriveSetup::default()
    };
    let world = world_for(map, &camera, &options.obstacles)?;
    let start = world.start;
    let mut twin = crate::sim::Twin::new(world, &config.robot, &config.sim, options.seed);
    let monitor = CollisionMonitor::new(&config.safety, config.robot.footprint_radius);
    let mut rng = ChaCha8Rng::seed_from_u64(options.seed ^ 0x7a95);
    let mut odom = Pose2::new(0.0, 0.0, 0.0);
    let mut run = RouteRun::new(map, waypoints, setup, start, odom).map_err(|e| e.to_string())?;
    let mut report = RouteReport {
        task: options.task.clone(),
        seed: options.seed,
        completed: false,
        planned: run.planned().to_vec(),
        legs_driven: 0,
        arrivals: Vec::new(),
        turn_errors_deg: Vec::new(),
        end_side_m: None,
        end_along_m: None,
        end_heading_deg: None,
        blocked: Vec::new(),
        collisions: 0,
        failure: None,
        sensor: options.sensor,
        detection: None,
        sim_time: 0.0,
        wall_time_s: None,
        realtime_factor: None,
    };
    let mut scan_points = Vec::new();
    let mut scan_age: Option<f64> = None;
    let period = options.period;
    let mut t = 0.0;
    while t < options.time_limit && !matches!(run.phase(), Phase::Done | Phase::Failed) {
        let truth = twin.pose();
        let seen = eyes.see(map, truth, &mut rng, stopwatch)?;
        let target = match run.phase() {
            Phase::Turn { target, .. } => Some(target),
            _ => None,
        };
        let driving = run.driving_leg();
        let ((v, w), events) = run.step(map, odom, &seen);
        for e in &events {
            match e {
                DriveEvent::Arrived { tag, .. } => {
                    report.arrivals.push(arrival(map, *tag, truth, &camera));
                }
                DriveEvent::Turned { .. } => {
                    if let Some(target) = target {
                        report
                            .turn_errors_deg
                            .push(wrap_angle(target - truth.theta).to_degrees());
                    }
                }
                DriveEvent::Done => report.completed = true,
                DriveEvent::Failed { why, .. } => report.failure = Some(why.clone()),
                DriveEvent::Aligned { .. } => {}
            }
        }
        let command = Twist::new(v, w);
        let verdict = monitor.check(
            command,
            &Obstacles {
                points: &scan_points,
                age: scan_age,
                source: SourceKind::Scan,
            },
        );
        // Held by a zone for an obstacle (not for want of a fresh scan, which only waits).
        let held = command.linear.abs() > 0.0
            && verdict.command.linear.abs() < 1e-9
            && verdict.acted.is_some()
            && !verdict.blocked;
        if let (Some(leg), true) = (driving, held) {
            // The monitor holds the robot on a leg: that edge is blocked. Back to the
            // leg's start and plan the rest again without it (and its way back).
            if let Err(why) = run.block(map, leg, odom) {
                report.failure = Some(why);
                break;
            }
            twin.set_command(Twist::ZERO);
        } else {
            twin.set_command(verdict.command);
        }
        twin.step(period);
        let frame = twin.take_frame();
        if let Some(wheels) = frame.wheels {
            odom = predict_pose(odom, wheels, config.robot.track);
        }
        if let Some(scan) = &frame.scan {
            scan_points = points_from_scan(scan, Pose2::default());
            scan_age = Some(0.0);
        } else if let Some(age) = scan_age.as_mut() {
            *age += period;
        }
        t += period;
    }
    twin.set_command(Twist::ZERO);
    if report.completed {
        let truth = twin.pose();
        let last = *run.route().tags.last().unwrap_or(&map.dock);
        let end = arrival(map, last, truth, &camera);
        let heading = map.tags[&last].zone.heading();
        let off = wrap_angle(truth.theta - heading);
        // Square to the zone's axis either way round.
        let off = wrap_angle(off - (off / std::f64::consts::PI).round() * std::f64::consts::PI);
        report.end_side_m = Some(end.side_m);
        report.end_along_m = Some(end.along_m);
        report.end_heading_deg = Some(off.to_degrees());
    }
    if !report.completed && report.failure.is_none() {
        report.failure = Some(format!("not done within {:.0} s", options.time_limit));
    }
    (report.sensor, report.detection) = eyes.finish();
    report.legs_driven = report.arrivals.len();
    report.blocked = run.blocked_edges().to_vec();
    report.collisions = twin.collisions();
    report.sim_time = t;
    Ok(report)
}

/// Where the image centre's floor point stands from `tag`, by the truth, along the
/// robot's heading and to its left.
fn arrival(map: &TagMap, tag: TagId, truth: Pose2, camera: &TagCamera) -> TagArrival {
    let t = &map.tags[&tag];
    let (s, c) = truth.theta.sin_cos();
    let centre = camera.centre(truth);
    let (dx, dy) = (centre.x - t.x, centre.y - t.y);
    TagArrival {
        tag,
        along_m: c * dx + s * dy,
        side_m: -s * dx + c * dy,
    }
}
