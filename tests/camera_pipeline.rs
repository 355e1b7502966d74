//! The camera on its own threads (feature `vision`): the newest frame wins, detections
//! ride along in the link's frames (`--camera`), and frames arrive over a ROS 2 image
//! topic.
#![cfg(feature = "vision")]

use crate::common;
use crate::vision_support;

use common::until;
use navdeck::geometry::{Point2, Pose2};
use navdeck::link::RobotLink;
use navdeck::link::camera::WithCamera;
use navdeck::link::ros2::image::Ros2ImageSource;
use navdeck::msgs::ros as msgs;
use navdeck::perception::aruco::Detector;
use navdeck::perception::colour::CameraImage;
use navdeck::perception::config::VisionConfig;
use navdeck::perception::frame::GrayFrame;
use navdeck::perception::pipeline::{CameraPipeline, FrameSource};
use navdeck::sim::Marker;
use navdeck::sim::rendered_camera::Renderer;
use rand::SeedableRng;
use std::sync::atomic::Ordering;
use std::time::Duration;
use vision_support::level;

/// The frame of a wall marker `id` 1 m straight ahead.
fn frame_with(cfg: &VisionConfig, detector: &Detector, id: u32) -> GrayFrame {
    let marker = Marker {
        id,
        position: Point2::new(1.0, 0.0),
        normal: std::f64::consts::PI,
    };
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(u64::from(id));
    Renderer::new(&cfg.markers, &cfg.render)
        .render(detector, Pose2::default(), [&marker], &[], &mut rng)
        .unwrap()
}

/// Hands out its frames as fast as asked, then nothing.
struct Burst(Vec<GrayFrame>);

impl FrameSource for Burst {
    fn grab(&mut self) -> Result<Option<CameraImage>, String> {
        if self.0.is_empty() {
            // A real camera blocks for its next frame; this one has none left.
            std::thread::sleep(Duration::from_millis(10));
            return Ok(None);
        }
        Ok(Some(self.0.remove(0).into()))
    }
}

#[test]
fn the_newest_frame_wins_and_its_markers_reach_the_console_through_the_link() {
    let cfg = level();
    let detector = Detector::from_config(&cfg).unwrap();
    let frames: Vec<GrayFrame> = (1..=6).map(|id| frame_with(&cfg, &detector, id)).collect();
    let pipeline = CameraPipeline::start(Box::new(Burst(frames)), detector, None, None);
    let counts = pipeline.counts();
    until("every frame to be detected or dropped", || {
        counts.grabbed.load(Ordering::SeqCst) == 6
            && counts.detected.load(Ordering::SeqCst) + counts.dropped.load(Ordering::SeqCst) == 6
    });
    let (_, app_link) = common::recording_app();
    let mut link = WithCamera::new(Box::new(app_link), pipeline, "burst".into());
    let frame = link.poll(0.1).unwrap();
    let status = frame.camera.expect("a camera status");
    // Whatever was dropped on the way, the last frame is the one reported.
    assert_eq!(status.ids, vec![6]);
    let sightings = frame.sightings.expect("sightings");
    assert_eq!(sightings.len(), 1);
    assert!((sightings[0].range - 1.0).abs() < 0.05, "{sightings:?}");
    assert!(link.label().contains("camera burst"));
    // Taken once: the next poll has no camera news.
    assert!(link.poll(0.2).unwrap().camera.is_none());
}

#[test]
fn frames_from_a_ros2_image_topic_are_detected() {
    let cfg = level();
    let detector = Detector::from_config(&cfg).unwrap();
    let frame = frame_with(&cfg, &detector, 421);
    let domain = 69;
    // The publisher: a camera driver on its own participant.
    let publisher = std::thread::spawn(move || {
        let participant = ros2_client::dds::rustdds::DomainParticipantBuilder::new(domain)
            .build()
            .unwrap();
        let context = ros2_client::Context::from_domain_participant(participant).unwrap();
        let mut node = context
            .new_node(
                ros2_client::NodeName::new("/", "camera_driver").unwrap(),
                ros2_client::NodeOptions::new().enable_rosout(false),
            )
            .unwrap();
        let qos = ros2_client::QosProfile::publisher_default().reliability_best_effort();
        let topic = node
            .create_topic(
                &ros2_client::Name::new("/camera", "image_raw").unwrap(),
                ros2_client::MessageTypeName::new("sensor_msgs", "Image"),
                &qos,
            )
            .unwrap();
        let images = node
            .create_publisher::<msgs::Image>(&topic, Some(qos))
            .unwrap();
        for _ in 0..200 {
            let _ = images.publish(msgs::Image {
                header: msgs::Header::new(msgs::Time::default(), "camera"),
                height: frame.height as u32,
                width: frame.width as u32,
                encoding: "mono8".into(),
                is_bigendian: 0,
                step: frame.width as u32,
                data: frame.data.clone(),
            });
            std::thread::sleep(Duration::from_millis(50));
        }
    });
    let source =
        Ros2ImageSource::connect(&Default::default(), domain, "/camera/image_raw").unwrap();
    let pipeline = CameraPipeline::start(Box::new(source), detector, None, None);
    let mut seen = None;
    until("a detection from the image topic", || {
        seen = pipeline.take_latest().filter(|(s, _, _)| !s.is_empty());
        seen.is_some()
    });
    let (sightings, status, _) = seen.unwrap();
    assert_eq!(status.ids, vec![421]);
    assert_eq!(sightings[0].id, 421);
    drop(pipeline);
    drop(publisher);
}
