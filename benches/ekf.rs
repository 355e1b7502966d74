//! One prediction and one single-sighting correction at n = 10, 100, 500, 1000 landmarks.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use nalgebra::Matrix3;
use navdeck::config::SlamConfig;
use navdeck::data::{MarkerSighting, WheelTravel};
use navdeck::geometry::{Pose2, wrap_angle};
use navdeck::slam::ekf::EkfSlam;

/// A filter holding `n` landmarks on a spiral around the robot.
fn filter_with(n: usize) -> EkfSlam {
    let mut f = EkfSlam::new(
        Pose2::default(),
        Matrix3::from_diagonal_element(1e-4),
        &SlamConfig::default(),
        0.11,
    );
    for i in 0..n {
        let range = 0.5 + 0.01 * i as f64;
        let bearing = wrap_angle(i as f64 * 2.399);
        f.correct(MarkerSighting {
            id: i as u32 + 1,
            range,
            bearing,
        });
    }
    f
}

fn predict_and_correct(c: &mut Criterion) {
    let mut group = c.benchmark_group("ekf_predict_plus_correct");
    for n in [10usize, 100, 500, 1000] {
        let mut f = filter_with(n);
        let mut k = 0usize;
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, &n| {
            b.iter(|| {
                f.predict(WheelTravel {
                    left: 0.0010,
                    right: 0.0012,
                });
                // A sighting that agrees with the estimate, so it is never gated out.
                k = (k + 7) % n;
                let l = f.landmark(k as u32 + 1).unwrap();
                let p = f.pose();
                let (dx, dy) = (l.mean.x - p.x, l.mean.y - p.y);
                f.correct(MarkerSighting {
                    id: k as u32 + 1,
                    range: dx.hypot(dy),
                    bearing: wrap_angle(dy.atan2(dx) - p.theta),
                })
            })
        });
    }
    group.finish();
}

criterion_group!(benches, predict_and_correct);
criterion_main!(benches);
