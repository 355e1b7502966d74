//! Lidar SLAM measured against the twin's truth: round a corridor loop over 30 m long,
//! where the loop closure must pull the drift back, and a whole mission in a generated
//! flat with no markers on its walls.

use navdeck::config::Config;
use navdeck::geometry::{Point2, Pose2, Twist, wrap_angle};
use navdeck::sim::Twin;
use navdeck::sim::generate::{GenerateOptions, Style, generate};
use navdeck::slam::lidar::{LidarSlam, LidarSlamConfig};
use navdeck::slam::odometry::Odometry;

/// The corners of the loop's centreline in a generated ring of `size`, counter-clockwise
/// from the one nearest the start, and the twin in it.
fn ring(seed: u64, size: (f64, f64)) -> (Twin, Vec<Point2>) {
    let options = GenerateOptions {
        seed,
        size: Some(size),
        style: Style::Loop,
        obstacles: 0,
        blocks: 2,
        wall_markers: false,
        ..GenerateOptions::default()
    };
    let mut world = generate(&options).unwrap();
    // Nothing loose in the corridor for this drive.
    world.blocks.clear();
    // The island: every wall but the boundary's four.
    let island = &world.walls[4..];
    let xs = island.iter().flat_map(|s| [s.a.x, s.b.x]);
    let ys = island.iter().flat_map(|s| [s.a.y, s.b.y]);
    let (lo_x, hi_x) = xs.fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(x), b.max(x)));
    let (lo_y, hi_y) = ys.fold((f64::MAX, f64::MIN), |(a, b), y| (a.min(y), b.max(y)));
    let (hw, hh) = (world.width / 2.0, world.height / 2.0);
    let (x0, x1) = ((-hw + lo_x) / 2.0, (hi_x + hw) / 2.0);
    let (y0, y1) = ((-hh + lo_y) / 2.0, (hi_y + hh) / 2.0);
    let mut corners = vec![
        Point2::new(x0, y0),
        Point2::new(x1, y0),
        Point2::new(x1, y1),
        Point2::new(x0, y1),
    ];
    let config = Config::default();
    let mut twin = Twin::new(world, &config.robot, &config.sim, seed);
    let first = (0..4)
        .min_by(|&a, &b| {
            let d = |k: usize| corners[k].distance(twin.pose().position());
            d(a).total_cmp(&d(b))
        })
        .unwrap();
    corners.rotate_left(first);
    let to_next = corners[1];
    let c = corners[0];
    twin.teleport(Pose2::new(
        c.x,
        c.y,
        (to_next.y - c.y).atan2(to_next.x - c.x),
    ));
    (twin, corners)
}

/// What one drive round the loop measured.
#[derive(Debug)]
struct LoopDrive {
    length: f64,
    /// The estimate's position error against the truth: just before the loop closed, just
    /// after, and the largest on the way.
    before: f64,
    after: f64,
    largest: f64,
    /// Where odometry alone would have put the robot at the end.
    odometry_error: f64,
    closures: usize,
}

/// Drives once round the corners and back to the first (the steering reads the twin's
/// true pose: this measures the estimator, not the follower), mapping with lidar SLAM.
fn drive_round(mut twin: Twin, corners: &[Point2]) -> LoopDrive {
    let config = Config::default();
    let start = twin.pose();
    let mut odometry = Odometry::new(start, config.robot.track);
    let mut slam = LidarSlam::new(&LidarSlamConfig::default(), start, start);
    let mut route: Vec<Point2> = corners[1..].to_vec();
    route.push(corners[0]);
    // Past the start again, far enough for a keyframe beside the first ones.
    let back = corners[0].distance(corners[1]).min(1.0);
    let along = (corners[1].x - corners[0].x, corners[1].y - corners[0].y);
    let n = along.0.hypot(along.1);
    route.push(Point2::new(
        corners[0].x + along.0 / n * back,
        corners[0].y + along.1 / n * back,
    ));
    let (mut before, mut after, mut largest, mut length) = (f64::NAN, f64::NAN, 0.0f64, 0.0);
    let mut closures = 0;
    let mut last = start.position();
    let mut t = 0.0;
    for goal in route {
        while twin.pose().position().distance(goal) > 0.05 && t < 900.0 {
            let p = twin.pose();
            let bearing = wrap_angle((goal.y - p.y).atan2(goal.x - p.x) - p.theta);
            let v = if bearing.abs() < 0.3 { 0.2 } else { 0.0 };
            twin.set_command(Twist::new(v, (2.0 * bearing).clamp(-1.5, 1.5)));
            twin.step(0.1);
            t += 0.1;
            let frame = twin.take_frame();
            if let Some(w) = frame.wheels {
                odometry.update(w);
            }
            let truth = twin.pose();
            length += truth.position().distance(last);
            last = truth.position();
            let error = |slam: &LidarSlam| {
                let estimate = slam.pose(odometry.pose());
                estimate.position().distance(truth.position())
            };
            if let Some(scan) = frame.scan {
                let was = error(&slam);
                let update = slam.update(odometry.pose(), &scan);
                if update.closure.is_some() {
                    closures += 1;
                    if before.is_nan() {
                        (before, after) = (was, error(&slam));
                    }
                }
            }
            largest = largest.max(error(&slam));
        }
    }
    let odometry_error = odometry.pose().position().distance(twin.pose().position());
    LoopDrive {
        length,
        before,
        after,
        largest,
        odometry_error,
        closures,
    }
}

#[test]
fn a_corridor_loop_over_30_m_closes_when_the_robot_comes_back() {
    for seed in [1, 2] {
        let (twin, corners) = ring(seed, (12.0, 6.0));
        let d = drive_round(twin, &corners);
        eprintln!("seed {seed}: {d:?}");
        assert!(d.length >= 30.0, "the loop is {:.1} m", d.length);
        assert!(d.closures >= 1, "no loop closed: {d:?}");
        // The first closure comes back to the start: afterwards the estimate is within
        // a few centimetres, and no worse than before.
        assert!(d.after < 0.05 && d.after <= d.before + 0.01, "{d:?}");
        assert!(d.largest < 0.3, "{d:?}");
        assert!(
            d.odometry_error > d.after,
            "odometry alone did better: {d:?}"
        );
    }
}
