//! One inverse-kinematics solve, closed form plus refinement, for random reachable
//! targets (FK of random in-limit joints from a seeded generator): the 4dof solver with
//! the pitch asked, with the pitch left free, and the 2dof solver. Seed 000 section 4.5.2
//! reports 2.01 ms on average and 3.64 ms at worst for its Python solver; navdeck's
//! target is under 5 us.

use criterion::{Criterion, criterion_group, criterion_main};
use navdeck::arm::{ArmConfig, Joints, Solver, Target, forward, inverse};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::hint::black_box;

/// Targets per set: the bench cycles through them.
const TARGETS: usize = 1024;

fn random_joints(cfg: &ArmConfig, rng: &mut ChaCha8Rng) -> Joints {
    Joints(std::array::from_fn(|i| {
        rng.random_range(cfg.limits.min[i]..=cfg.limits.max[i])
    }))
}

/// Reachable targets for `cfg` with the pitch asked or not; for 2dof the wrist keeps the
/// fixed pitch.
fn targets(cfg: &ArmConfig, with_pitch: bool, seed: u64) -> Vec<Target> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut out = Vec::with_capacity(TARGETS);
    while out.len() < TARGETS {
        let mut q = random_joints(cfg, &mut rng);
        if cfg.solver == Solver::TwoDof {
            let o = cfg.joint_offsets;
            let p3 = q.0[1] + o[1] + q.0[2] + o[2];
            q.0[3] = cfg.fixed_pitch - p3 - o[3];
            if !(cfg.limits.min[3]..=cfg.limits.max[3]).contains(&q.0[3]) {
                continue;
            }
        }
        let p = forward(cfg, &q);
        out.push(if with_pitch {
            Target::from(p)
        } else {
            Target::point(p.x, p.y, p.z)
        });
    }
    out
}

fn solve(c: &mut Criterion) {
    let four = ArmConfig::default();
    let two = ArmConfig {
        solver: Solver::TwoDof,
        ..ArmConfig::default()
    };
    let sets = [
        ("4dof_pitch_asked", &four, targets(&four, true, 1)),
        ("4dof_pitch_free", &four, targets(&four, false, 2)),
        ("2dof", &two, targets(&two, false, 3)),
    ];
    let mut group = c.benchmark_group("arm_ik");
    for (name, cfg, set) in &sets {
        let current = Joints(cfg.poses.home);
        let mut k = 0usize;
        group.bench_function(*name, |b| {
            b.iter(|| {
                k = (k + 1) % set.len();
                inverse(cfg, black_box(&set[k]), &current).expect("reachable")
            })
        });
    }
    group.finish();
}

criterion_group!(benches, solve);
criterion_main!(benches);
