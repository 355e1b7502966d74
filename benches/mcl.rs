//! One Monte-Carlo localisation update on the TurtleBot3 world: 1000 particles, 60 of the
//! lidar's 360 beams, with the likelihood field and with the beam model. `mcl_weigh` times
//! the measurement model alone, so the rest of the update (motion sampling, resampling,
//! the estimate) is the difference.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use navdeck::config::Config;
use navdeck::data::LaserScan;
use navdeck::geometry::Pose2;
use navdeck::slam::mcl::config::{
    LocalizationConfig, MeasurementModel, ParticleCount, SensorModel, UpdateSchedule,
};
use navdeck::slam::mcl::sensor::{Beams, Weigher};
use navdeck::slam::mcl::{KnownMap, Mcl};
use std::path::Path;
use std::sync::Arc;

const MAP: &str = "maps/turtlebot3_world.yaml";

/// The map, and a scan the twin's lidar took at `at`.
fn map_and_scan(at: Pose2) -> (navdeck::map::grid::OccupancyGrid, LaserScan) {
    let grid = navdeck::map::io::load(Path::new(MAP)).unwrap().grid;
    let world = navdeck::sim::nav2_world::from_grid(&grid, Some(at), Path::new(MAP)).unwrap();
    let config = Config::default();
    let mut twin = navdeck::sim::Twin::new(world, &config.robot, &config.sim, 1);
    let mut scan = None;
    while scan.is_none() {
        twin.step(0.05);
        scan = twin.take_frame().scan;
    }
    (grid, scan.unwrap())
}

fn config(model: SensorModel) -> LocalizationConfig {
    LocalizationConfig {
        measurement: MeasurementModel {
            model,
            ..MeasurementModel::default()
        },
        particles: ParticleCount {
            min_particles: 1000,
            max_particles: 1000,
            ..ParticleCount::default()
        },
        schedule: UpdateSchedule {
            // Every call is an update.
            update_min_d: 0.0,
            update_min_a: 0.0,
            ..UpdateSchedule::default()
        },
        ..LocalizationConfig::default()
    }
}

fn bench(c: &mut Criterion) {
    let at = Pose2::new(-1.0, 0.5, 0.3);
    let (grid, scan) = map_and_scan(at);
    let map = Arc::new(KnownMap::new(&grid).unwrap());
    let models = [
        ("likelihood_field", SensorModel::LikelihoodField),
        ("beam", SensorModel::Beam),
    ];
    let mut weigh = c.benchmark_group("mcl_weigh");
    for (name, model) in models {
        let cfg = config(model);
        let mut weigher = Weigher::new(&map, &cfg.measurement, scan.range_max);
        let beams = Beams::pick(&scan, cfg.measurement.max_beams);
        let mut mcl = Mcl::new(map.clone(), &cfg, 1);
        mcl.init_at(at, 0.1, 0.1);
        let poses: Vec<Pose2> = mcl.particles().iter().map(|p| p.pose).collect();
        weigh.bench_with_input(BenchmarkId::from_parameter(name), &poses, |b, poses| {
            b.iter(|| {
                poses
                    .iter()
                    .map(|&p| weigher.log_likelihood(&map, p, &beams))
                    .sum::<f64>()
            })
        });
    }
    // The beam model in cells it has not traced from yet.
    let cfg = config(SensorModel::Beam);
    let mut weigher = Weigher::new(&map, &cfg.measurement, scan.range_max);
    let beams = Beams::pick(&scan, cfg.measurement.max_beams);
    let mut mcl = Mcl::new(map.clone(), &cfg, 1);
    mcl.init_at(at, 0.1, 0.1);
    let poses: Vec<Pose2> = mcl.particles().iter().map(|p| p.pose).collect();
    weigh.bench_function("beam_untraced", |b| {
        b.iter(|| {
            weigher.forget_traced();
            poses
                .iter()
                .map(|&p| weigher.log_likelihood(&map, p, &beams))
                .sum::<f64>()
        })
    });
    weigh.finish();
    let mut update = c.benchmark_group("mcl_update");
    for (name, model) in models {
        let cfg = config(model);
        let mut mcl = Mcl::new(map.clone(), &cfg, 1);
        mcl.init_at(at, 0.1, 0.1);
        let mut k = 0u64;
        update.bench_function(BenchmarkId::from_parameter(name), |b| {
            b.iter(|| {
                // Odometry that steps back and forth 2 cm, so every update moves.
                k += 1;
                let dx = if k.is_multiple_of(2) { 0.02 } else { 0.0 };
                mcl.update(Pose2::new(dx, 0.0, 0.0), &scan)
            })
        });
    }
    update.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
