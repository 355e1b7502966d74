//! Keepout and speed zones in the running pilot: on generated worlds a keepout square
//! across the straight line from the start to a goal is neither planned through nor
//! driven into (the twin's true pose), and inside a speed zone the true speed stays
//! under its limit. The zones' Nav2 filter masks read back through an independent reader
//! (tests/interop/nav2_mask_check.py).

use crate::common::{self, scratch};
use crate::python_support;
use navdeck::config::Config;
use navdeck::geometry::Point2;
use navdeck::link::runtime::Runtime;
use navdeck::link::sim::SimLink;
use navdeck::map::grid::OccupancyGrid;
use navdeck::map::zones::mask::{self, MaskKind};
use navdeck::map::zones::raster::Frame;
use navdeck::map::zones::{Rect, SpeedLimit, Zone, ZoneList};
use navdeck::pilot::Intent;
use navdeck::pilot::mode::Mode;
use navdeck::pilot::navigation::Target;
use navdeck::pilot::zones::ZoneAsk;
use navdeck::sim::generate::{GenerateOptions, Style, generate};
use navdeck::sim::{Twin, World};
use std::process::Command;

const PERIOD: f64 = 0.1;
/// The speed zone's limit, m/s (the follower cruises at `[plan] max_speed`, 0.2 m/s).
const LIMIT: f64 = 0.08;
/// How far over the limit the true speed may read (one period's position noise), m/s.
const SPEED_TOLERANCE: f64 = 0.01;

/// What one run found.
#[derive(Debug, Default)]
struct Run {
    planned: bool,
    arrived: bool,
    /// A replan found no way round (the keepout and the walls close the way).
    no_way_round: bool,
    /// Planned and driven (true) poses inside the keepout zone.
    planned_inside: usize,
    driven_inside: usize,
    /// The fastest true speed while the true centre was inside the speed zone, m/s.
    fastest_in_speed_zone: Option<f64>,
    collisions: u32,
}

/// A square of side `side` centred on `c`.
fn square(c: Point2, side: f64) -> Rect {
    let h = side / 2.0;
    Rect {
        x0: c.x - h,
        y0: c.y - h,
        x1: c.x + h,
        y1: c.y + h,
    }
}

fn lerp(a: Point2, b: Point2, t: f64) -> Point2 {
    Point2::new(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y))
}

/// A goal 2 to 3.5 m from the start with the straight line between them clear of walls,
/// boxes and blocks, if the world has one.
fn goal_for(world: &World) -> Option<Point2> {
    let grid: OccupancyGrid = world.rasterize(0.05);
    let blocks: Vec<Point2> = world.blocks.iter().map(|b| b.pose.position()).collect();
    let (w, h) = (world.width, world.height);
    let clear = |p: Point2, r: f64| {
        common::clear_round(&grid, (w, h), p, r) && blocks.iter().all(|b| b.distance(p) > 0.4)
    };
    let start = world.start.position();
    let line_clear = |b: Point2| {
        let n = (start.distance(b) / 0.05).ceil() as usize;
        (0..=n).all(|k| clear(lerp(start, b, k as f64 / n as f64), 0.25))
    };
    let mut best: Option<Point2> = None;
    let mut y = -h / 2.0;
    while y < h / 2.0 {
        let mut x = -w / 2.0;
        while x < w / 2.0 {
            let p = Point2::new(x, y);
            let d = p.distance(start);
            if (2.0..3.5).contains(&d)
                && clear(p, 0.35)
                && best.is_none_or(|b| d > b.distance(start))
                && line_clear(p)
            {
                best = Some(p);
            }
            x += 0.25;
        }
        y += 0.25;
    }
    best
}

/// Plans from the start to a goal across a keepout square (0.6 m, on the line's middle)
/// past a speed zone (0.5 m, 80 % of the way), drives there headless for up to
/// `seconds`, and counts what went where.
fn run(world: World, seed: u64, seconds: f64) -> Option<Run> {
    let goal = goal_for(&world)?;
    let start = world.start.position();
    let keepout = square(lerp(start, goal, 0.5), 0.6);
    let speed = square(lerp(start, goal, 0.8), 0.5);
    let config = Config::default();
    let twin = Twin::new(world, &config.robot, &config.sim, seed);
    let mut robot = Runtime::new(
        Box::new(SimLink::new(twin, 0.0)),
        config.pilot_settings(),
        0.0,
    );
    let zones = [
        Zone::keepout(keepout),
        Zone::speed(SpeedLimit::MetresPerSecond(LIMIT), speed),
    ];
    let mut out = Run::default();
    let mut intents: Vec<Intent> = zones
        .into_iter()
        .map(|z| Intent::Zones(ZoneAsk::Add(z)))
        .collect();
    intents.push(Intent::Goto(Target::Point(goal)));
    robot.tick(0.0, intents);
    out.planned = robot.pilot().route().is_some();
    if !out.planned {
        return Some(out);
    }
    robot.tick(PERIOD, vec![Intent::Mode(Mode::PathFollowing)]);
    let truth = |r: &Runtime| r.link().ground_truth().expect("the twin knows").pose();
    let mut last = truth(&robot).position();
    let mut t = PERIOD;
    while t < seconds && !robot.pilot().arrived() {
        t += PERIOD;
        let stepped = robot.tick(t, Vec::new());
        out.no_way_round |= format!("{:?}", stepped.events).contains("no path to");
        if let Some(route) = robot.pilot().route() {
            let points = route.plan.trajectory.points.iter().map(|p| p.position);
            out.planned_inside += points.filter(|&p| keepout.contains(p)).count();
        }
        let now = truth(&robot).position();
        if keepout.contains(now) {
            out.driven_inside += 1;
        }
        if speed.contains(now) {
            let v = now.distance(last) / PERIOD;
            out.fastest_in_speed_zone = Some(out.fastest_in_speed_zone.unwrap_or(0.0).max(v));
        }
        last = now;
    }
    out.arrived = robot.pilot().arrived();
    out.collisions = robot.link().ground_truth().expect("twin").collisions();
    Some(out)
}

fn world(seed: u64, style: Style) -> World {
    let options = GenerateOptions {
        seed,
        style,
        obstacles: 3,
        blocks: 2,
        ..GenerateOptions::default()
    };
    generate(&options).expect("a world")
}

#[test]
fn a_keepout_across_the_way_is_never_planned_or_driven_and_the_speed_zone_is_kept() {
    let mut arrivals = 0;
    for (seed, style) in [(3, Style::Boxes), (5, Style::Rooms), (8, Style::Boxes)] {
        let Some(r) = run(world(seed, style), seed, 90.0) else {
            continue;
        };
        let case = format!("{style} seed {seed}: {r:?}");
        assert_eq!(r.planned_inside, 0, "{case}");
        assert_eq!(r.driven_inside, 0, "{case}");
        if let Some(v) = r.fastest_in_speed_zone {
            assert!(v <= LIMIT + SPEED_TOLERANCE, "{case}");
        }
        arrivals += usize::from(r.arrived);
    }
    assert!(
        arrivals >= 2,
        "the robot went round the keepout and arrived"
    );
}

#[test]
fn a_goal_inside_a_keepout_zone_is_refused() {
    let config = Config::default();
    let twin = Twin::new(world(3, Style::Boxes), &config.robot, &config.sim, 3);
    let mut robot = Runtime::new(
        Box::new(SimLink::new(twin, 0.0)),
        config.pilot_settings(),
        0.0,
    );
    let here = robot.pilot().estimated_pose().position();
    let goal = Point2::new(here.x + 0.8, here.y);
    let zone = Zone::keepout(square(goal, 0.4));
    let stepped = robot.tick(
        0.0,
        vec![
            Intent::Zones(ZoneAsk::Add(zone)),
            Intent::Goto(Target::Point(goal)),
        ],
    );
    assert!(robot.pilot().route().is_none());
    let said = format!("{:?}", stepped.events);
    assert!(said.contains("inside keepout zone 1"), "{said}");
}

/// Holds forward for `seconds` (repeated every tick, as a terminal repeats a key) in
/// `mode`; the true positions after each tick.
fn hold_forward(robot: &mut Runtime, mode: Mode, seconds: f64) -> Vec<Point2> {
    use navdeck::pilot::teleop::DriveKey;
    robot.tick(0.0, vec![Intent::Mode(mode)]);
    let mut seen = Vec::new();
    let steps = (seconds / PERIOD).round() as u32;
    for k in 1..=steps {
        let key = Intent::KeyDown {
            key: DriveKey::Forward,
            repeat: k > 1,
        };
        robot.tick(k as f64 * PERIOD, vec![key]);
        seen.push(robot.link().ground_truth().expect("twin").pose().position());
    }
    seen
}

/// A robot facing its goal across the keepout, with `zones`.
fn facing_goal(seed: u64, zones: impl Fn(Point2, Point2) -> Vec<Zone>) -> (Runtime, Vec<Zone>) {
    let mut w = world(seed, Style::Boxes);
    let goal = goal_for(&w).expect("a goal");
    let start = w.start.position();
    w.start.theta = (goal.y - start.y).atan2(goal.x - start.x);
    let config = Config::default();
    let twin = Twin::new(w, &config.robot, &config.sim, seed);
    let mut robot = Runtime::new(
        Box::new(SimLink::new(twin, 0.0)),
        config.pilot_settings(),
        0.0,
    );
    let zones = zones(start, goal);
    let asks = zones
        .iter()
        .map(|z| Intent::Zones(ZoneAsk::Add(*z)))
        .collect();
    robot.tick(0.0, asks);
    (robot, zones)
}

#[test]
fn teleop_and_race_keep_to_a_speed_zone_and_stop_at_a_keepout_edge() {
    for mode in [Mode::Manual, Mode::Race] {
        let (mut robot, zones) = facing_goal(3, |start, goal| {
            vec![
                Zone::speed(SpeedLimit::MetresPerSecond(0.05), square(start, 1.2)),
                Zone::keepout(square(lerp(start, goal, 0.5), 0.6)),
            ]
        });
        let seen = hold_forward(&mut robot, mode, 30.0);
        let (speed, keepout) = (zones[0].rect, zones[1].rect);
        let fastest = seen
            .windows(2)
            .filter(|w| speed.contains(w[1]))
            .map(|w| w[1].distance(w[0]) / PERIOD)
            .fold(0.0, f64::max);
        assert!(
            fastest > 0.03,
            "{mode:?}: the robot drove ({fastest:.3} m/s)"
        );
        assert!(
            fastest <= 0.05 + SPEED_TOLERANCE,
            "{mode:?}: {fastest:.3} m/s in the zone"
        );
        assert!(
            seen.iter().all(|p| !keepout.contains(*p)),
            "{mode:?}: the robot drove into the keepout zone"
        );
        // It drove up to the keepout and the collision monitor stopped it at the edge.
        let nearest = seen
            .iter()
            .map(|p| keepout.distance(*p))
            .fold(f64::MAX, f64::min);
        assert!(
            nearest < 0.4,
            "{mode:?}: stopped {nearest:.2} m short of the keepout"
        );
    }
}

#[test]
fn the_mission_explores_round_a_keepout_zone_without_entering_it() {
    let (mut robot, zones) = facing_goal(3, |start, goal| {
        vec![Zone::keepout(square(lerp(start, goal, 0.5), 0.6))]
    });
    let keepout = zones[0].rect;
    robot.tick(PERIOD, vec![Intent::Mode(Mode::Exploration)]);
    let mut t = PERIOD;
    let mut nearest = f64::MAX;
    while t < 240.0 {
        t += PERIOD;
        robot.tick(t, Vec::new());
        let p = robot.link().ground_truth().expect("twin").pose().position();
        assert!(
            !keepout.contains(p),
            "at {t:.1} s the robot is inside the keepout"
        );
        nearest = nearest.min(keepout.distance(p));
        if let Some(route) = robot.pilot().route() {
            let mut points = route.plan.trajectory.points.iter();
            assert!(
                points.all(|q| !keepout.contains(q.position)),
                "a leg through it"
            );
        }
    }
    assert!(
        nearest < 1.0,
        "the mission came near the zone ({nearest:.2} m)"
    );
    assert_eq!(robot.link().ground_truth().expect("twin").collisions(), 0);
}

/// 50 generated worlds (styles from the seed), a keepout across the straight line to a
/// goal and a speed zone near it; prints what was planned and driven inside them.
#[test]
#[ignore = "a 50-world sweep for the figures; a few seconds per world"]
fn sweep() {
    let (mut runs, mut planned, mut arrived, mut collisions) = (0, 0, 0, 0);
    let mut no_way = 0;
    let (mut planned_inside, mut driven_inside) = (0, 0);
    let mut fastest: f64 = 0.0;
    let mut seed = 0u64;
    while runs < 50 && seed < 500 {
        seed += 1;
        let style = Style::ALL[seed as usize % Style::ALL.len()];
        let Ok(w) = generate(&GenerateOptions {
            seed,
            style,
            obstacles: 3,
            blocks: 2,
            ..GenerateOptions::default()
        }) else {
            continue;
        };
        let Some(r) = run(w, seed, 120.0) else {
            continue;
        };
        runs += 1;
        planned += usize::from(r.planned);
        arrived += usize::from(r.arrived);
        no_way += usize::from(!r.arrived && r.no_way_round);
        planned_inside += r.planned_inside;
        driven_inside += r.driven_inside;
        collisions += r.collisions;
        if let Some(v) = r.fastest_in_speed_zone {
            fastest = fastest.max(v);
        }
        if r.planned_inside + r.driven_inside > 0 || !r.arrived {
            println!("seed {seed} {style}: {r:?}");
        }
    }
    println!(
        "worlds {runs}: planned {planned}, arrived {arrived}, no way round {no_way}; planned \
         poses inside keepout {planned_inside}, driven (true) poses inside keepout \
         {driven_inside}; fastest true speed inside the {LIMIT} m/s zone {fastest:.3} m/s; \
         collisions {collisions}"
    );
    assert_eq!(planned_inside + driven_inside, 0);
}

/// Our masks as a Nav2 user's tools read them: tests/interop/nav2_mask_check.py parses the
/// filter info and map_server YAML and the PGM itself, applies map_server's and the
/// costmap filters' rules, and says each zone centre's filter value.
#[test]
fn masks_read_back_through_an_independent_nav2_reader() {
    let Some(python) = python_support::python("the Nav2 mask reader", "only the standard library")
    else {
        return;
    };
    let dir = scratch("masks");
    let map = dir.join("lab.yaml");
    let zones = ZoneList::new(vec![
        Zone::keepout(Rect {
            x0: -0.5,
            y0: 0.0,
            x1: 0.5,
            y1: 0.25,
        }),
        Zone::speed(
            SpeedLimit::MetresPerSecond(0.12),
            square(Point2::new(1.0, 1.0), 0.4),
        ),
        Zone::speed(
            SpeedLimit::MetresPerSecond(0.3),
            square(Point2::new(-1.0, -1.0), 0.4),
        ),
    ])
    .unwrap();
    let frame = Frame {
        resolution: 0.05,
        origin: Point2::new(-2.0, -2.0),
        width: 80,
        height: 80,
    };
    for kind in MaskKind::ALL {
        for (path, bytes) in mask::encode(&zones, kind, &map, frame, 0.22) {
            std::fs::write(path, bytes).unwrap();
        }
    }
    let script = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/interop/nav2_mask_check.py"
    );
    let ask = |kind: MaskKind, points: &[(f64, f64)]| -> Vec<f64> {
        let info = mask::paths(&map, kind).2;
        let mut cmd = Command::new(&python);
        cmd.arg(script).arg(&info);
        for (x, y) in points {
            cmd.arg(format!("{x},{y}"));
        }
        let out = cmd.output().expect("run the mask reader");
        assert!(
            out.status.success(),
            "nav2_mask_check.py: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let text = String::from_utf8(out.stdout).unwrap();
        text.split_whitespace()
            .map(|v| v.parse().unwrap())
            .collect()
    };
    // Keepout (type 0): the mask value is the cost, 100 lethal inside, 0 outside.
    let keepout = ask(MaskKind::Keepout, &[(0.0, 0.1), (0.0, 0.4), (0.45, 0.2)]);
    assert_eq!(keepout, vec![100.0, 0.0, 100.0]);
    // Speed (type 2): base + multiplier * value in m/s; 0 (no limit) outside.
    let speed = ask(MaskKind::Speed, &[(1.0, 1.0), (-1.0, -1.0), (0.0, 0.0)]);
    assert!((speed[0] - 0.12).abs() < 1e-6, "{speed:?}");
    assert!((speed[1] - 0.3).abs() < 1e-6, "{speed:?}");
    assert_eq!(speed[2], 0.0);
}
