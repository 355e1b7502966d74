//! Detection plus pose on an 864x480 frame with 10 markers in view (seed 001 reports
//! 20-30 ms for detection on the robot). Needs `--features vision`.

use criterion::{Criterion, criterion_group, criterion_main};
use navdeck::geometry::{Point2, Pose2};
use navdeck::perception::aruco::Detector;
use navdeck::perception::config::VisionConfig;
use navdeck::perception::frame::GrayFrame;
use navdeck::sim::Marker;
use navdeck::sim::rendered_camera::Renderer;
use rand::SeedableRng;
use std::hint::black_box;

/// Ten markers on a wall 1.5 m ahead of a level camera, spread across the view.
fn scene() -> (Detector, GrayFrame) {
    let mut cfg = VisionConfig::default();
    cfg.mount.rotation_deg = [-90.0, 0.0, -90.0];
    cfg.mount.translation = [0.03, 0.0, 0.10];
    let detector = Detector::from_config(&cfg).unwrap();
    let markers: Vec<Marker> = (0..10)
        .map(|i| Marker {
            id: 1 + i,
            position: Point2::new(1.5, 0.9 - 0.2 * f64::from(i)),
            normal: std::f64::consts::PI,
        })
        .collect();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
    let frame = Renderer::new(&cfg.markers, &cfg.render)
        .render(&detector, Pose2::default(), &markers, &[], &mut rng)
        .unwrap();
    (detector, frame)
}

fn bench(c: &mut Criterion) {
    let (detector, frame) = scene();
    let found = detector.detect(&frame, None).unwrap();
    assert_eq!(found.sightings.len(), 10, "ids {:?}", found.ids);
    c.bench_function("aruco detect+pose 864x480, 10 markers", |b| {
        b.iter(|| detector.detect(black_box(&frame), None).unwrap())
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
