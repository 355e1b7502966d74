//! One collision-monitor check with a TurtleBot3's 360-beam scan and the default `[safety]`
//! zones (stop, slowdown, approach on the Burger's 0.105 m footprint), the scan turned
//! into points included: in an open room where no zone acts, heading for a wall 0.3 m
//! ahead (the approach zone finds the contact on its 45th step), and on a curve (0.5 rad/s)
//! into a corner; `collision_monitor_zones` times the same checks on points already made.
//! The monitor runs once per 0.1 s control step.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use navdeck::control::collision_monitor::{
    CollisionMonitor, Obstacles, SafetyConfig, SourceKind, points_from_scan,
};
use navdeck::data::LaserScan;
use navdeck::geometry::{Pose2, Twist};
use std::f64::consts::PI;
use std::hint::black_box;

/// The Burger's footprint radius, m.
const FOOTPRINT: f64 = 0.105;

/// A 360-beam scan (LDS-01: 0.12 m to 3.5 m) from inside a box room whose walls lie
/// `ahead`, `left`, `behind` and `right` of the robot, square to it.
fn room_scan(ahead: f64, left: f64, behind: f64, right: f64) -> LaserScan {
    let increment = 2.0 * PI / 360.0;
    let ranges = (0..360)
        .map(|k| {
            let (s, c) = (-PI + k as f64 * increment).sin_cos();
            // The nearest wall along the beam.
            let along_x = if c > 0.0 { ahead / c } else { -behind / c };
            let along_y = if s > 0.0 { left / s } else { -right / s };
            let r = along_x.min(along_y);
            if r <= 3.5 { r as f32 } else { f32::INFINITY }
        })
        .collect();
    LaserScan {
        angle_min: -PI,
        angle_increment: increment,
        range_min: 0.12,
        range_max: 3.5,
        ranges,
    }
}

fn bench(c: &mut Criterion) {
    let monitor = CollisionMonitor::new(&SafetyConfig::default(), FOOTPRINT);
    let cases = [
        (
            "open_room",
            room_scan(2.0, 1.5, 2.0, 1.5),
            Twist::new(0.22, 0.0),
        ),
        (
            "wall_0.3m_ahead",
            room_scan(0.3, 0.5, 2.0, 0.5),
            Twist::new(0.22, 0.0),
        ),
        (
            "curve_into_corner",
            room_scan(0.5, 0.6, 2.0, 0.6),
            Twist::new(0.22, 0.5),
        ),
    ];
    let mut group = c.benchmark_group("collision_monitor_check");
    for (name, scan, command) in &cases {
        group.bench_with_input(BenchmarkId::from_parameter(name), scan, |b, scan| {
            b.iter(|| {
                let points = points_from_scan(black_box(scan), Pose2::default());
                let obstacles = Obstacles {
                    points: &points,
                    age: Some(0.1),
                    source: SourceKind::Scan,
                };
                monitor.check(black_box(*command), &obstacles)
            })
        });
    }
    group.finish();
    // The zones alone, on points already in the robot's frame.
    let mut zones = c.benchmark_group("collision_monitor_zones");
    for (name, scan, command) in &cases {
        let points = points_from_scan(scan, Pose2::default());
        zones.bench_with_input(BenchmarkId::from_parameter(name), &points, |b, points| {
            let obstacles = Obstacles {
                points,
                age: Some(0.1),
                source: SourceKind::Scan,
            };
            b.iter(|| monitor.check(black_box(*command), black_box(&obstacles)))
        });
    }
    zones.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
