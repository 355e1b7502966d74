//! The rendered camera drawing only what the detector can read (`navdeck mission
//! --sim-camera`) reports exactly the sightings of the whole frame, and leaves the twin's
//! random generator where the whole frame leaves it, from poses all over generated
//! worlds and close in front of their blocks (feature `vision`).
#![cfg(feature = "vision")]

use navdeck::config::Config;
use navdeck::geometry::{Point2, Pose2, Segment};
use navdeck::map::grid::FREE;
use navdeck::perception::config::VisionConfig;
use navdeck::sim::generate::{GenerateOptions, Style, generate};
use navdeck::sim::rendered_camera::RenderedCamera;
use navdeck::sim::{BlockState, CameraFrames, Marker, World};
use rand::{Rng, RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A camera of the default config drawing `frames`.
fn camera(frames: CameraFrames) -> RenderedCamera {
    let max_range = Config::default().sim.camera.max_range;
    let mut c = RenderedCamera::new(&VisionConfig::default(), max_range, None).unwrap();
    c.set_frames(frames);
    c
}

/// Poses with 0.12 m of free space round them, anywhere in `world`, any heading.
fn free_poses(world: &World, n: usize, seed: u64) -> Vec<Pose2> {
    let grid = world.rasterize(0.05);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let clear = |p: Point2| {
        (0..8).all(|k| {
            let a = f64::from(k) * std::f64::consts::FRAC_PI_4;
            grid.at(Point2::new(p.x + 0.12 * a.cos(), p.y + 0.12 * a.sin())) == FREE
        })
    };
    let mut poses = Vec::new();
    while poses.len() < n {
        let p = Point2::new(
            rng.random_range(-world.width / 2.0..world.width / 2.0),
            rng.random_range(-world.height / 2.0..world.height / 2.0),
        );
        if clear(p) {
            poses.push(Pose2::new(p.x, p.y, rng.random_range(-3.2..3.2)));
        }
    }
    poses
}

/// Poses from 0.2 m to 0.6 m in front of each of `markers`, looking at it a little askew.
fn close_ups(markers: &[Marker]) -> Vec<Pose2> {
    let mut poses = Vec::new();
    for m in markers {
        for (k, d) in [0.2, 0.3, 0.45, 0.6].into_iter().enumerate() {
            let (s, c) = m.normal.sin_cos();
            let skew = 0.15 * (k as f64 - 1.5);
            poses.push(Pose2::new(
                m.position.x + d * c,
                m.position.y + d * s,
                m.normal + std::f64::consts::PI + skew,
            ));
        }
    }
    poses
}

#[derive(Default)]
struct Tally {
    frames: usize,
    sightings: usize,
    empty: usize,
}

/// Captures every pose with both cameras from the same generator state and compares.
fn compare(world: &World, poses: &[Pose2], tally: &mut Tally) {
    let blocks: Vec<BlockState> = world.blocks.iter().map(BlockState::from_block).collect();
    let block_markers: Vec<Marker> = blocks.iter().flat_map(|b| b.current_markers()).collect();
    let block_edges: Vec<Segment> = blocks.iter().flat_map(|b| b.edges()).collect();
    let occluders: [&[Segment]; 2] = [&world.walls, &block_edges];
    let markers: Vec<&Marker> = world.markers.iter().chain(&block_markers).collect();
    let (mut whole, mut readable) = (camera(CameraFrames::Whole), camera(CameraFrames::Readable));
    for (k, &pose) in poses.iter().enumerate() {
        let mut a = ChaCha8Rng::seed_from_u64(k as u64);
        let mut b = a.clone();
        let (want, status) = whole.capture(pose, markers.iter().copied(), &occluders, &mut a);
        let (got, _) = readable.capture(pose, markers.iter().copied(), &occluders, &mut b);
        assert!(status.error.is_none(), "{status:?}");
        assert_eq!(
            got, want,
            "{}: sightings from {pose:?} (whole frame decoded {:?})",
            world.name, status.ids
        );
        assert_eq!(a.next_u64(), b.next_u64(), "the generator moved on alike");
        tally.frames += 1;
        tally.sightings += want.len();
        tally.empty += usize::from(want.is_empty());
    }
}

#[test]
fn drawing_only_what_can_be_read_gives_the_whole_frames_sightings() {
    let mut tally = Tally::default();
    for (seed, style) in [(1, Style::Boxes), (2, Style::Rooms), (3, Style::Corridors)] {
        let world = generate(&GenerateOptions {
            seed,
            style,
            ..GenerateOptions::default()
        })
        .unwrap();
        let blocks: Vec<Marker> = world
            .blocks
            .iter()
            .flat_map(|b| BlockState::from_block(b).current_markers())
            .collect();
        let mut poses = free_poses(&world, 100, seed);
        poses.extend(close_ups(&blocks));
        poses.extend(close_ups(&world.markers[..world.markers.len().min(6)]));
        compare(&world, &poses, &mut tally);
    }
    let Tally {
        frames,
        sightings,
        empty,
    } = tally;
    eprintln!("{frames} frames, {sightings} sightings, {empty} frames without one");
    // The comparison covered frames with sightings and frames without.
    assert!(
        sightings > frames,
        "{sightings} sightings in {frames} frames"
    );
    assert!(empty > 5, "{empty} frames without a sighting");
}

#[test]
fn a_marker_too_far_to_be_accepted_is_not_drawn_and_the_whole_frame_agrees() {
    // 4.5 m straight ahead, facing the camera: beyond the sensor's 3 m.
    let far = Marker {
        id: 7,
        position: Point2::new(4.5, 0.0),
        normal: std::f64::consts::PI,
    };
    let pose = Pose2::new(0.0, 0.0, 0.0);
    let (mut whole, mut readable) = (camera(CameraFrames::Whole), camera(CameraFrames::Readable));
    let mut a = ChaCha8Rng::seed_from_u64(9);
    let mut b = a.clone();
    let (want, whole_status) = whole.capture(pose, [&far], &[], &mut a);
    let (got, status) = readable.capture(pose, [&far], &[], &mut b);
    assert!(want.is_empty() && got.is_empty(), "{want:?} {got:?}");
    // The whole frame decodes it and refuses it for its range; nothing was drawn for it.
    assert_eq!(whole_status.ids, vec![7], "{whole_status:?}");
    assert!(status.ids.is_empty() && status.thumbnail.is_none() && status.error.is_none());
    assert_eq!(a.next_u64(), b.next_u64(), "the generator moved on alike");
}
