//! The collision monitor in the running pilot: held drive keys towards walls, boxes and
//! blocks in generated worlds stop short of them, and the robot can back away.

use navdeck::config::Config;
use navdeck::geometry::Pose2;
use navdeck::link::runtime::Runtime;
use navdeck::link::sim::SimLink;
use navdeck::pilot::Intent;
use navdeck::pilot::behaviours::Behaviour;
use navdeck::pilot::mode::Mode;
use navdeck::pilot::teleop::DriveKey;
use navdeck::sim::generate::{GenerateOptions, Style, generate};
use navdeck::sim::{Twin, World};

const PERIOD: f64 = 0.1;

fn rig(world: World, seed: u64) -> Runtime {
    rig_with(Config::default(), world, seed)
}

fn rig_with(config: Config, world: World, seed: u64) -> Runtime {
    let twin = Twin::new(world, &config.robot, &config.sim, seed);
    Runtime::new(
        Box::new(SimLink::new(twin, 0.0)),
        config.pilot_settings(),
        0.0,
    )
}

/// Holds `key` (repeated every tick, as a terminal repeats it) from `from` for `seconds`;
/// whether the collision monitor had control at any tick.
fn hold(robot: &mut Runtime, key: DriveKey, from: f64, seconds: f64) -> bool {
    let mut monitored = false;
    let steps = (seconds / PERIOD).round() as u32;
    for k in 1..=steps {
        let t = from + k as f64 * PERIOD;
        robot.tick(t, vec![Intent::KeyDown { key, repeat: k > 1 }]);
        let winner = robot.pilot().arbiter().winner().map(|(b, _)| b);
        monitored |= winner == Some(Behaviour::CollisionMonitor);
    }
    robot.tick(from + seconds + PERIOD, vec![Intent::KeyUp(key)]);
    monitored
}

fn truth(robot: &Runtime) -> (Pose2, u32) {
    let truth = robot.link().ground_truth().expect("the twin knows");
    (truth.pose(), truth.collisions())
}

#[test]
fn holding_forward_at_walls_boxes_and_blocks_stops_short_and_backing_away_is_allowed() {
    let mut stopped = 0;
    for (k, style) in [Style::Boxes, Style::Rooms, Style::Corridors]
        .into_iter()
        .enumerate()
    {
        for seed in 1..=3u64 {
            for quarter in 0..4 {
                let options = GenerateOptions {
                    seed,
                    style,
                    obstacles: 4,
                    blocks: 4,
                    ..GenerateOptions::default()
                };
                let mut world = generate(&options).expect("a world");
                world.start.theta = quarter as f64 * std::f64::consts::FRAC_PI_2 + 0.3;
                let mut robot = rig(world, seed + 10 * k as u64);
                let mode = if quarter % 2 == 0 {
                    Mode::Manual
                } else {
                    Mode::Race
                };
                robot.tick(0.0, vec![Intent::Mode(mode)]);
                let monitored = hold(&mut robot, DriveKey::Forward, 0.0, 25.0);
                let (at_wall, touched) = truth(&robot);
                let case = format!("{style} seed {seed}, start turned {quarter}/4, {mode:?}");
                assert_eq!(touched, 0, "{case}: the robot touched something");
                if !monitored {
                    continue;
                }
                stopped += 1;
                // Backing away from what stopped it is allowed.
                hold(&mut robot, DriveKey::Backward, 25.2, 1.0);
                let (backed, touched) = truth(&robot);
                assert_eq!(touched, 0, "{case}: backing away touched something");
                let moved = backed.position().distance(at_wall.position());
                assert!(moved > 0.05, "{case}: backed only {moved:.3} m");
            }
        }
    }
    assert!(
        stopped >= 18,
        "the monitor stopped only {stopped} of 36 drives"
    );
}

#[test]
fn without_zones_the_same_drive_runs_into_the_wall() {
    let mut config = Config::default();
    config.safety.polygons.clear();
    let world = generate(&GenerateOptions::default()).expect("a world");
    let mut robot = rig_with(config, world, 1);
    let monitored = hold(&mut robot, DriveKey::Forward, 0.0, 25.0);
    assert!(!monitored);
    assert!(
        truth(&robot).1 > 0,
        "held forward for 25 s, the robot touched nothing"
    );
}

/// The nearest range the lidar reads within 10° of straight ahead, metres.
fn nearest_ahead(robot: &Runtime) -> Option<f64> {
    let (_, scan) = robot.pilot().newest_scan()?;
    (scan.ranges.iter().enumerate())
        .filter(|&(k, &r)| {
            let a = scan.angle_min + k as f64 * scan.angle_increment;
            let a = navdeck::geometry::wrap_angle(a);
            a.abs() <= 10f64.to_radians() && f64::from(r) >= scan.range_min
        })
        .map(|(_, &r)| f64::from(r))
        .reduce(f64::min)
}

/// `cargo test --all-features --test suite -- --ignored collision_monitor::sweep --nocapture`:
/// 100 generated worlds (styles, sizes, boxes and blocks drawn from the seed), a random
/// start heading, manual or race mode at a random speed, forward held for 30 s; prints the
/// stopping distances and how long the monitor took from first acting to a zero command.
#[test]
#[ignore = "a 100-world sweep for the figures; a few seconds per world"]
fn sweep() {
    use rand::{Rng, SeedableRng};
    let (mut gaps, mut touched, mut lags) = (Vec::new(), 0, Vec::new());
    for seed in 1..=100u64 {
        let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
        let style = Style::ALL[rng.random_range(0..Style::ALL.len())];
        let options = GenerateOptions {
            seed,
            style,
            obstacles: rng.random_range(2..6),
            blocks: rng.random_range(2..6),
            ..GenerateOptions::default()
        };
        let Ok(mut world) = generate(&options) else {
            continue;
        };
        world.start.theta = rng.random_range(-std::f64::consts::PI..std::f64::consts::PI);
        let mut robot = rig(world, seed);
        let mode = if rng.random_bool(0.5) {
            Mode::Manual
        } else {
            Mode::Race
        };
        robot.tick(0.0, vec![Intent::Mode(mode)]);
        // Speed keys up a random number of times (race starts faster).
        for k in 0..rng.random_range(0..6) {
            robot.tick(
                0.01 * (k + 1) as f64,
                vec![Intent::Speed(navdeck::pilot::teleop::SpeedChange::SpeedUp)],
            );
        }
        let (mut first, mut zero) = (None, None);
        for k in 1..=300 {
            let t = 0.1 + k as f64 * PERIOD;
            let key = Intent::KeyDown {
                key: DriveKey::Forward,
                repeat: k > 1,
            };
            robot.tick(t, vec![key]);
            let monitor = robot.pilot().arbiter().winner().map(|(b, _)| b)
                == Some(Behaviour::CollisionMonitor);
            if monitor && first.is_none() {
                first = Some(t);
            }
            if first.is_some() && zero.is_none() && robot.pilot().commanded().linear == 0.0 {
                zero = Some(t);
            }
        }
        let (_, hits) = truth(&robot);
        if hits > 0 {
            let speed = robot.pilot().teleop().limits();
            println!("seed {seed}: {style} {mode:?} speeds {speed:?}: {hits} contacts");
        }
        touched += hits;
        if let (Some(f), Some(z)) = (first, zero) {
            lags.push(z - f);
        }
        if let Some(gap) = nearest_ahead(&robot) {
            gaps.push(gap - Config::default().robot.footprint_radius);
        }
    }
    gaps.sort_by(f64::total_cmp);
    lags.sort_by(f64::total_cmp);
    println!(
        "runs {} collisions {touched}; gap to the obstacle ahead: min {:.3} m, median {:.3} m; \
         first acting to zero command: median {:.1} s, max {:.1} s",
        gaps.len(),
        gaps[0],
        gaps[gaps.len() / 2],
        lags[lags.len() / 2],
        lags[lags.len() - 1]
    );
    assert_eq!(touched, 0);
}
