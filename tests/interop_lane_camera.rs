//! Lane mode on a real robot's camera: a TurtleBot3 publishes JPEG frames as
//! sensor_msgs/CompressedImage on `camera/image_raw/compressed` (played by
//! tests/interop/lane_camera_peer.py on Eclipse Cyclone DDS), navdeck's ROS 2 camera
//! source decodes them, and the lane pipeline reads the same lane from them as from the
//! picture before it was compressed.

use crate::cyclone_peer::LinePeer;
use navdeck::config::Config;
use navdeck::geometry::Pose2;
use navdeck::perception::colour::{BgrFrame, CameraImage};
use navdeck::perception::lane::{LanePipeline, LaneVisionConfig};
use navdeck::perception::lane_camera::LaneCameraConfig;
use navdeck::perception::pipeline::FrameSource;
use navdeck::sim::World;
use navdeck::sim::track::Lighting;
use navdeck::sim::track_render::TrackRenderer;
use rand::SeedableRng;
use std::path::Path;
use std::time::Instant;

/// A frame of the built-in track from 3 cm left of the lane's centre, 1 m along it.
fn track_frame(camera: &LaneCameraConfig) -> BgrFrame {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/maps/track.toml");
    let world = World::load(Path::new(path)).unwrap();
    let scene = world.track.as_ref().unwrap();
    let (p, heading) = scene.track.at(1.0);
    let (s, c) = heading.sin_cos();
    let pose = Pose2::new(p.x - 0.03 * s, p.y + 0.03 * c, heading);
    let lighting = Lighting::parse("normal").unwrap();
    let mut renderer = TrackRenderer::new(scene, &world.walls, &[], camera, lighting, 1);
    renderer.render(pose, 0.0, &mut rand_chacha::ChaCha8Rng::seed_from_u64(1))
}

/// The lane error the pipeline settles on over `frames` (its filter spans 5 frames).
fn settled_error(camera: &LaneCameraConfig, frames: &[BgrFrame]) -> f64 {
    let mut pipeline = LanePipeline::new(&LaneVisionConfig::default(), camera).unwrap();
    let mut last = None;
    for f in frames {
        last = Some(pipeline.read(f, None));
    }
    let s = last.expect("a frame");
    assert!(s.yellow.is_some() && s.white.is_some(), "{s:?}");
    s.error_px.expect("a lane error")
}

#[test]
fn lane_mode_reads_a_turtlebots_compressed_camera_frames_as_it_reads_the_twins() {
    let camera = LaneCameraConfig::default();
    let frame = track_frame(&camera);
    let path = crate::common::scratch("lane_camera_peer").join("frame.jpg");
    let jpeg = navdeck::perception::compressed::encode_jpeg(&frame, 90).unwrap();
    std::fs::write(&path, jpeg).unwrap();
    let Some(mut peer) = LinePeer::start_with("lane_camera_peer.py", 96, &[path.to_str().unwrap()])
    else {
        return;
    };
    let mut config = Config::default();
    config.ros2.interfaces = vec!["127.0.0.1".into()];
    let mut source = navdeck::link::ros2::image::Ros2ImageSource::connect(
        &config.ros2,
        96,
        "camera/image_raw/compressed",
    )
    .expect("the compressed camera subscription");
    let mut decoded = Vec::new();
    let give_up = Instant::now() + std::time::Duration::from_secs_f64(crate::PATIENCE);
    while decoded.len() < 6 {
        assert!(Instant::now() < give_up, "{} frames arrived", decoded.len());
        match source.grab().expect("a decodable frame") {
            Some(CameraImage::Colour(f)) => decoded.push(f),
            Some(CameraImage::Gray(_)) => panic!("a colour JPEG decoded as grey"),
            None => {}
        }
    }
    assert!(peer.next_line("published").contains("published"));
    let f = &decoded[0];
    assert_eq!((f.width, f.height), (frame.width, frame.height));
    let before = settled_error(&camera, &vec![frame; 6]);
    let after = settled_error(&camera, &decoded);
    // 3 cm left of centre: the lane's centre lies right, a positive error of ~30 px
    // (bird's-eye millimetres), and JPEG's artefacts move it by a few at most.
    assert!(before > 15.0, "{before}");
    assert!(
        (after - before).abs() < 5.0,
        "{before} before, {after} after JPEG"
    );
}
