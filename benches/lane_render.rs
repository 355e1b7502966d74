//! What one frame of the twin's lane camera costs: `maps/track.toml` at 640x480 from
//! poses along the lane, plainly lit and under dark light, shadows and glare at once. A
//! lane run draws 10 frames a twin second and must keep 30 times real time, OpenCV's
//! perception included, so a frame should take a few milliseconds at most.

use criterion::{Criterion, criterion_group, criterion_main};
use navdeck::geometry::Pose2;
use navdeck::perception::lane_camera::LaneCameraConfig;
use navdeck::sim::World;
use navdeck::sim::track::Lighting;
use navdeck::sim::track_render::TrackRenderer;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::path::Path;

/// Poses along the lane a benchmark iteration renders from.
const POSES: usize = 10;

fn bench(c: &mut Criterion) {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/maps/track.toml");
    let world = World::load(Path::new(path)).unwrap();
    let scene = world.track.as_ref().unwrap();
    let boxes: Vec<_> = world
        .obstacles
        .iter()
        .map(|o| (o.pose, o.width, o.height))
        .collect();
    let poses: Vec<Pose2> = (0..POSES)
        .map(|i| {
            let (p, heading) = scene
                .track
                .at(i as f64 * scene.track.length() / POSES as f64);
            Pose2::new(p.x, p.y, heading)
        })
        .collect();
    let camera = LaneCameraConfig::default();
    for (name, lighting) in [
        ("lane_render_640x480_normal", "normal"),
        (
            "lane_render_640x480_dark_shadows_glare",
            "dark+shadows+glare",
        ),
    ] {
        let lighting = Lighting::parse(lighting).unwrap();
        let mut renderer = TrackRenderer::new(scene, &world.walls, &boxes, &camera, lighting, 1);
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let mut i = 0;
        c.bench_function(name, |b| {
            b.iter(|| {
                i = (i + 1) % POSES;
                renderer.render(poses[i], i as f64, &mut rng)
            })
        });
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
