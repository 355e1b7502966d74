//! How fast the twin runs headless: 60 s of simulated time in the default arena, stepped in
//! 0.1 s control periods with the lidar on while driving a gentle curve. Throughput is in
//! simulated seconds per wall-clock second, i.e. the real-time factor.

use criterion::{BatchSize, Criterion, Throughput, criterion_group, criterion_main};
use navdeck::config::Config;
use navdeck::geometry::Twist;
use navdeck::sim::{Twin, World};
use std::hint::black_box;

const SIM_SECONDS: u64 = 60;

fn run(mut twin: Twin) -> Twin {
    // A 0.5 m circle around (-1, -1) from the arena's start pose: clear of everything.
    twin.set_command(Twist::new(0.2, 0.4));
    for _ in 0..SIM_SECONDS * 10 {
        twin.step(0.1);
        black_box(twin.take_frame());
    }
    twin
}

fn twin_realtime_factor(c: &mut Criterion) {
    let config = Config::default();
    assert!(config.sim.lidar.enabled);
    let world = World::default_arena();
    let check = run(Twin::new(world.clone(), &config.robot, &config.sim, 1));
    assert_eq!(check.collisions(), 0, "the benchmark curve must stay clear");
    let mut group = c.benchmark_group("twin");
    group.throughput(Throughput::Elements(SIM_SECONDS));
    group.bench_function("arena_60s_lidar", |b| {
        b.iter_batched(
            || Twin::new(world.clone(), &config.robot, &config.sim, 7),
            run,
            BatchSize::SmallInput,
        )
    });
    group.finish();
}

criterion_group!(benches, twin_realtime_factor);
criterion_main!(benches);
