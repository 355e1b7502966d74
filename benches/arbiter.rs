//! The arbiter's overhead per control step (seed 000 §5.3's priority pick): the pick among
//! a task's proposal and the collision monitor's, as the pilot makes it every 0.1 s, and
//! the pick among every behaviour at once with a change of winner each time (the
//! transition recorded in the 100-long history).

use criterion::{Criterion, criterion_group, criterion_main};
use navdeck::geometry::Twist;
use navdeck::pilot::behaviours::{Arbiter, Behaviour, Proposal};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let task = Proposal::new(Behaviour::Teleop, Twist::new(0.2, 0.0), "driving by keys");
    let monitor = Proposal::new(
        Behaviour::CollisionMonitor,
        Twist::new(0.0, 0.0),
        "stopping, obstacle 0.14 m ahead in `stop`",
    );
    let usual = [monitor.clone(), task.clone()];
    let mut arbiter = Arbiter::default();
    let mut t = 0.0;
    c.bench_function("arbiter_two_proposals", |b| {
        b.iter(|| {
            t += 0.1;
            black_box(arbiter.arbitrate(t, black_box(&usual)))
        })
    });
    let all: Vec<Proposal> = (Behaviour::ALL.iter())
        .map(|&b| Proposal::new(b, Twist::new(0.1, 0.0), b.name()))
        .collect();
    let mut arbiter = Arbiter::default();
    let mut k = 0usize;
    c.bench_function("arbiter_ten_proposals_new_winner", |b| {
        b.iter(|| {
            // Drop the top one every other step: the winner changes every step.
            k += 1;
            let from = k % 2;
            black_box(arbiter.arbitrate(k as f64 * 0.1, black_box(&all[from..])))
        })
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
