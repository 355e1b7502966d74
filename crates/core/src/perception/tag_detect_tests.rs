//! The tag detector on the twin's rendered frames: a tag in view is found with its id and
//! the pose the ideal camera gives, a tag running off the image is never reported with a
//! wrong pose, and ids the map does not hold are counted and left out.

use super::*;
use crate::geometry::Pose2;
use crate::perception::tag_patterns::TagPatterns;
use crate::sim::tag_camera::TagCamera;
use crate::sim::tag_render::TagRenderer;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

const MAP: &str = "
tags:
  508: {x: 0.0, y: 0.0, type: dock, zone: DOCK}
  101: {x: 0.6, y: 0.0, type: waypoint, zone: A}
  117: {x: 0.6, y: 0.6, type: shelf, zone: B}
edges:
  508: [{to: 101, direction: forward, type: straight}]
  101: [{to: 508, direction: backward, type: straight}, {to: 117, direction: forward, type: pivot}]
  117: [{to: 101, direction: backward, type: pivot}]
tasks:
  out: {waypoints: [508, 101, 117, 101, 508]}
";

/// Tolerances on a rendered tag's pose: the ideal camera's own noise (offset sd 2 mm,
/// angle sd 0.2°), so the rendered camera measures at least as well as the camera the
/// route driver was first tried with. At 20 px a cell, a corner 0.1 px out moves the
/// centre about 0.03 mm and the angle about 0.04°: well inside.
const OFFSET_TOLERANCE: f64 = 0.002;
const ANGLE_TOLERANCE_DEG: f64 = 0.2;

struct Rig {
    map: TagMap,
    renderer: TagRenderer,
    detector: TagDetector,
    ideal: TagCamera,
}

fn rig(camera: &TagCameraConfig) -> Rig {
    let map = TagMap::parse(MAP).unwrap();
    let patterns = TagPatterns::new().unwrap().all(map.tags.keys().copied());
    let detector = TagDetector::new(camera, 0.05).unwrap();
    let ideal = TagCamera {
        look: detector.look(),
        ..TagCamera::default()
    };
    Rig {
        renderer: TagRenderer::new(&map, camera, 0.05, &patterns, 5),
        map,
        detector,
        ideal,
    }
}

impl Rig {
    fn detect(&self, pose: Pose2, seed: u64) -> TagFrame {
        let frame = self
            .renderer
            .render(pose, &mut ChaCha8Rng::seed_from_u64(seed));
        self.detector.detect(&frame, &self.map).unwrap()
    }

    /// How far `d` is from the truth: (ahead, lateral) metres and the angle, degrees.
    fn error(&self, d: &TagDetection, pose: Pose2) -> (f64, f64, f64) {
        let id = d.sighting.id;
        let truth = self.ideal.exact(id, &self.map.tags[&id], pose);
        (
            (d.sighting.ahead - truth.ahead).abs(),
            (d.sighting.lateral - truth.lateral).abs(),
            wrap_angle(d.sighting.align - truth.align)
                .abs()
                .to_degrees(),
        )
    }

    fn assert_true(&self, d: &TagDetection, pose: Pose2) {
        let (ahead, lateral, angle) = self.error(d, pose);
        assert!(
            ahead < OFFSET_TOLERANCE && lateral < OFFSET_TOLERANCE && angle < ANGLE_TOLERANCE_DEG,
            "tag {} from {pose:?}: off by {:.2} mm ahead, {:.2} mm lateral, {angle:.3}° ({d:?})",
            d.sighting.id,
            ahead * 1000.0,
            lateral * 1000.0,
        );
    }
}

#[test]
fn a_rendered_tag_is_found_with_its_id_and_the_ideal_cameras_pose() {
    let camera = TagCameraConfig::default();
    let rig = rig(&camera);
    let look = rig.detector.look();
    // Near tag 101 in several ways: short of it, past it, to either side, turned.
    let poses = [
        (0.6 - look - 0.05, 0.0, 0.0),
        (0.6 - look + 0.03, 0.02, 3f64.to_radians()),
        (0.6 - look, -0.08, -10f64.to_radians()),
        (0.6 - look - 0.02, 0.05, 30f64.to_radians()),
    ];
    for (x, y, theta) in poses {
        let pose = Pose2::new(x, y, theta);
        let seen = rig.detect(pose, 1);
        assert_eq!(seen.unknown, 0);
        assert_eq!(seen.detections.len(), 1, "{pose:?}: {seen:?}");
        let d = &seen.detections[0];
        assert_eq!(d.sighting.id, 101);
        rig.assert_true(d, pose);
        // Seed 003 §2.1's outputs: the centre pixel is the tag centre's projection, and
        // the camera-frame lateral is + right.
        let truth = rig.ideal.exact(101, &rig.map.tags[&101], pose);
        if truth.lateral.abs() > 0.005 {
            assert_eq!(d.camera_xyz[0] > 0.0, truth.lateral > 0.0, "{d:?}");
        }
        assert!((0.0..1280.0).contains(&d.centre_px[0]) && (0.0..720.0).contains(&d.centre_px[1]));
    }
    // Facing north over tag 117 (zone B), backed off a little and turned 5° right.
    let pose = Pose2::new(0.6, 0.6 - look - 0.04, 85f64.to_radians());
    let seen = rig.detect(pose, 2);
    assert_eq!(seen.detections.len(), 1, "{seen:?}");
    assert_eq!(seen.detections[0].sighting.id, 117);
    rig.assert_true(&seen.detections[0], pose);
    assert!(seen.detections[0].sighting.align < -4f64.to_radians());
}

#[test]
fn a_tag_running_off_the_image_is_never_reported_with_a_wrong_pose() {
    let camera = TagCameraConfig::default();
    let rig = rig(&camera);
    let look = rig.detector.look();
    let (mut whole, mut found) = (0, 0);
    // Tag 101 slides off the top of the image (the robot short of it), then off its
    // right side (the robot to the tag's left), a millimetre or two at a time.
    let ahead = (0..60).map(|k| Pose2::new(0.6 - look - 0.06 - 0.0015 * f64::from(k), 0.0, 0.0));
    let aside = (0..60).map(|k| Pose2::new(0.6 - look, 0.14 + 0.002 * f64::from(k), 0.0));
    for (k, pose) in ahead.chain(aside).enumerate() {
        let seen = rig.detect(pose, k as u64);
        whole += usize::from(rig.renderer.wholly_in_view(pose, 0.0).contains(&101));
        for d in &seen.detections {
            found += 1;
            rig.assert_true(d, pose);
        }
    }
    // The sweep covers tags whole in view and tags partly out of it.
    assert!(
        whole > 10 && whole < 110,
        "{whole} frames with the tag whole"
    );
    assert!(found > 10, "{found} tags found");
}

#[test]
fn ids_the_map_does_not_hold_are_counted_and_left_out() {
    let camera = TagCameraConfig::default();
    let rig = rig(&camera);
    let pose = Pose2::new(0.6 - rig.detector.look(), 0.0, 0.0);
    let frame = rig.renderer.render(pose, &mut ChaCha8Rng::seed_from_u64(3));
    let without_101 = TagMap::parse(&MAP.replace("101", "102")).unwrap();
    let seen = rig.detector.detect(&frame, &without_101).unwrap();
    assert_eq!((seen.detections.len(), seen.unknown), (0, 1), "{seen:?}");
    // A frame of the wrong size is an error, not a panic.
    let small = GrayFrame {
        width: 10,
        height: 10,
        data: vec![0; 100],
    };
    assert!(rig.detector.detect(&small, &rig.map).is_err());
}
