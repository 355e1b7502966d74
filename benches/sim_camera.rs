//! What one frame of the twin's rendered camera costs, drawn and read whole (the console's
//! camera panel) and only where a marker can be read (`navdeck mission --sim-camera`),
//! averaged over poses spread over a generated world. Needs `--features vision`.

use criterion::{Criterion, criterion_group, criterion_main};
use navdeck::config::Config;
use navdeck::geometry::{Point2, Pose2, Segment};
use navdeck::map::grid::FREE;
use navdeck::perception::config::VisionConfig;
use navdeck::sim::generate::{GenerateOptions, generate};
use navdeck::sim::rendered_camera::RenderedCamera;
use navdeck::sim::{BlockState, CameraFrames, Marker};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Frames a benchmark iteration captures.
const POSES: usize = 40;

fn bench(c: &mut Criterion) {
    let world = generate(&GenerateOptions {
        seed: 1,
        ..GenerateOptions::default()
    })
    .unwrap();
    let blocks: Vec<BlockState> = world.blocks.iter().map(BlockState::from_block).collect();
    let block_markers: Vec<Marker> = blocks.iter().flat_map(|b| b.current_markers()).collect();
    let block_edges: Vec<Segment> = blocks.iter().flat_map(|b| b.edges()).collect();
    let occluders: [&[Segment]; 2] = [&world.walls, &block_edges];
    let markers: Vec<&Marker> = world.markers.iter().chain(&block_markers).collect();
    // Poses in free space, any heading, as the robot drives about.
    let grid = world.rasterize(0.05);
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut poses = Vec::new();
    while poses.len() < POSES {
        let p = Point2::new(
            rng.random_range(-world.width / 2.0..world.width / 2.0),
            rng.random_range(-world.height / 2.0..world.height / 2.0),
        );
        if grid.at(p) == FREE {
            poses.push(Pose2::new(p.x, p.y, rng.random_range(-3.2..3.2)));
        }
    }
    let max_range = Config::default().sim.camera.max_range;
    for (frames, name) in [
        (
            CameraFrames::Whole,
            "sim camera: 40 frames drawn and read whole",
        ),
        (
            CameraFrames::Readable,
            "sim camera: 40 frames drawn and read where readable",
        ),
    ] {
        let mut camera = RenderedCamera::new(&VisionConfig::default(), max_range, None).unwrap();
        camera.set_frames(frames);
        let mut noise = ChaCha8Rng::seed_from_u64(1);
        c.bench_function(name, |b| {
            b.iter(|| {
                poses
                    .iter()
                    .map(|&pose| {
                        let (seen, _) =
                            camera.capture(pose, markers.iter().copied(), &occluders, &mut noise);
                        seen.len()
                    })
                    .sum::<usize>()
            })
        });
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
