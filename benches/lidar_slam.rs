//! Lidar SLAM: one scan matched against the local map (a generated 8 m x 6 m flat, no
//! wall markers, the twin's 360-beam lidar), and one solve of a pose graph of 100 and
//! 1000 keyframes with a loop closure every 50.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use nalgebra::{Matrix3, Vector3};
use navdeck::config::Config;
use navdeck::data::LaserScan;
use navdeck::geometry::Pose2;
use navdeck::sim::generate::{GenerateOptions, Style, generate};
use navdeck::slam::lidar::{Edge, EdgeKind, LidarSlam, LidarSlamConfig, PoseGraph};

/// The twin in a generated flat without wall markers.
fn twin() -> navdeck::sim::Twin {
    let options = GenerateOptions {
        seed: 3,
        size: Some((8.0, 6.0)),
        style: Style::Rooms,
        wall_markers: false,
        ..GenerateOptions::default()
    };
    let world = generate(&options).unwrap();
    let config = Config::default();
    navdeck::sim::Twin::new(world, &config.robot, &config.sim, 1)
}

/// A scan the twin's lidar takes at `at`.
fn scan_at(twin: &mut navdeck::sim::Twin, at: Pose2) -> LaserScan {
    twin.teleport(at);
    loop {
        twin.step(0.05);
        if let Some(scan) = twin.take_frame().scan {
            return scan;
        }
    }
}

fn scan_match(c: &mut Criterion) {
    let mut twin = twin();
    // Facing the start's longest free beam, so the drive below stays in the open.
    let first = twin.pose();
    let look = scan_at(&mut twin, first);
    let (k, _) = (look.ranges.iter().enumerate())
        .map(|(k, r)| {
            (
                k,
                if r.is_finite() {
                    *r
                } else {
                    look.range_max as f32
                },
            )
        })
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap();
    let heading = first.theta + look.angle_min + k as f64 * look.angle_increment;
    let start = Pose2::new(first.x, first.y, heading);
    let mut slam = LidarSlam::new(&LidarSlamConfig::default(), start, start);
    // A local map of keyframes 0.25 m apart along that heading.
    let ahead = |d: f64| start.compose(Pose2::new(d, 0.0, 0.0));
    for k in 0..6 {
        let at = ahead(0.25 * k as f64);
        let scan = scan_at(&mut twin, at);
        slam.update(at, &scan);
    }
    // Two poses 6 cm apart, past the matching step and short of a new keyframe: every
    // update is one match.
    let (a, b) = (ahead(1.28), ahead(1.34));
    let (scan_a, scan_b) = (scan_at(&mut twin, a), scan_at(&mut twin, b));
    let mut flip = true;
    c.bench_function("lidar_slam_scan_match", |bench| {
        bench.iter(|| {
            flip = !flip;
            let (at, scan) = if flip { (a, &scan_a) } else { (b, &scan_b) };
            assert!(slam.update(at, scan).matched);
        })
    });
}

/// A chain of `n` keyframes round a square spiral with odometry that turns 1° short at
/// each corner, and a loop closure from every 50th keyframe back to the first.
fn drifted_graph(n: usize) -> PoseGraph {
    let info = Matrix3::from_diagonal(&Vector3::new(2500.0, 2500.0, 10000.0));
    let mut g = PoseGraph {
        poses: vec![Pose2::default()],
        edges: Vec::new(),
    };
    for k in 1..n {
        let turn = if k % 10 == 0 {
            std::f64::consts::FRAC_PI_2
        } else {
            0.0
        };
        let measured = Pose2::new(0.2, 0.0, turn);
        let drifted = Pose2::new(0.2, 0.0, turn * 0.99);
        let last = g.poses[k - 1];
        g.poses.push(last.compose(drifted));
        g.edges.push(Edge {
            from: k - 1,
            to: k,
            relative: measured,
            information: info,
            kind: EdgeKind::Sequential,
        });
        if k % 50 == 0 {
            // Every 40 keyframes the square comes round: node k is where node k - 40 was.
            g.edges.push(Edge {
                from: k - 40,
                to: k,
                relative: Pose2::default(),
                information: info,
                kind: EdgeKind::Loop,
            });
        }
    }
    g
}

fn graph_optimisation(c: &mut Criterion) {
    let mut group = c.benchmark_group("lidar_slam_optimise");
    group.sample_size(20);
    for n in [100usize, 1000] {
        let graph = drifted_graph(n);
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            b.iter_batched(
                || graph.clone(),
                |mut g| g.optimize().unwrap(),
                criterion::BatchSize::LargeInput,
            )
        });
    }
    group.finish();
}

criterion_group!(benches, scan_match, graph_optimisation);
criterion_main!(benches);
