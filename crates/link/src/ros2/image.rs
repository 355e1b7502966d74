//! Camera frames from a ROS 2 image topic as a source for the camera pipeline, on a DDS
//! participant of its own: sensor_msgs/Image (mono8, rgb8 or bgr8), or, for a topic
//! ending in `/compressed` (image_transport's name, as a TurtleBot3 camera publishes),
//! sensor_msgs/CompressedImage (JPEG or PNG), decoded by OpenCV. With a camera_info
//! topic beside it (route mode's tag camera), the newest calibration rides along.

use super::config::Ros2Config;
use super::inbox::{Inbox, Urgency};
use super::participant::{Factory, Joined, join, qos_profile};
use crate::LinkError;
use navdeck_core::perception::colour::{BgrFrame, CameraImage};
use navdeck_core::perception::compressed::decode_compressed;
use navdeck_core::perception::frame::GrayFrame;
use navdeck_core::perception::intrinsics::Intrinsics;
use navdeck_core::perception::pipeline::FrameSource;
use navdeck_msgs::ros as msgs;
use ros2_client::{Context, Node};
use std::time::Duration;

/// How long one `grab` waits for a frame.
const GRAB_WAIT: Duration = Duration::from_millis(100);

/// The topic's messages: raw or compressed.
enum Images {
    Raw(Inbox<msgs::Image>),
    Compressed(Inbox<msgs::CompressedImage>),
}

pub struct Ros2ImageSource {
    images: Images,
    /// The camera's sensor_msgs/CameraInfo and its topic, when asked for.
    info: Option<(Inbox<msgs::CameraInfo>, String)>,
    /// The calibration last handed on (a driver repeats it with every frame).
    calibration: Option<Result<Intrinsics, String>>,
    _node: Node,
    _context: Context,
}

impl Ros2ImageSource {
    /// Subscribes to `topic` (sensor-data QoS, `[ros2] scan_qos`).
    pub fn connect(config: &Ros2Config, domain: u16, topic: &str) -> Result<Self, LinkError> {
        Self::connect_with_info(config, domain, topic, None)
    }

    /// Subscribes to `topic` and, when given, to the camera's calibration on
    /// `info_topic` (the same QoS: drivers publish it with each frame).
    pub fn connect_with_info(
        config: &Ros2Config,
        domain: u16,
        topic: &str,
        info_topic: Option<&str>,
    ) -> Result<Self, LinkError> {
        let Joined {
            context,
            namespace,
            mut node,
            ..
        } = join(config, domain, "navdeck_camera")?;
        let mut factory = Factory {
            node: &mut node,
            config,
            namespace: &namespace,
        };
        let qos = qos_profile(config.scan_qos, false);
        let images = if topic.ends_with("/compressed") {
            let kind = "CompressedImage";
            Images::Compressed(factory.inbox(
                "camera",
                topic,
                ("sensor_msgs", kind),
                qos.clone(),
                Urgency::Tick,
            )?)
        } else {
            Images::Raw(factory.inbox(
                "camera",
                topic,
                ("sensor_msgs", "Image"),
                qos.clone(),
                Urgency::Tick,
            )?)
        };
        let info = match info_topic {
            Some(t) => {
                let info = ("sensor_msgs", "CameraInfo");
                let sub = factory.inbox("camera_info", t, info, qos, Urgency::Tick)?;
                let shown = if t.starts_with('/') {
                    t.to_string()
                } else {
                    format!("{}/{t}", namespace.trim_end_matches('/'))
                };
                Some((sub, shown))
            }
            None => None,
        };
        Ok(Self {
            images,
            info,
            calibration: None,
            _node: node,
            _context: context,
        })
    }
}

impl FrameSource for Ros2ImageSource {
    fn take_calibration(&mut self) -> Option<Result<Intrinsics, String>> {
        self.newest_calibration()
    }

    fn grab(&mut self) -> Result<Option<CameraImage>, String> {
        let mut notes = Vec::new();
        let newest = match &mut self.images {
            Images::Raw(inbox) => inbox
                .wait_all("image", GRAB_WAIT, &mut notes)
                .pop()
                .map(raw),
            Images::Compressed(inbox) => (inbox.wait_all("image", GRAB_WAIT, &mut notes).pop())
                .map(|m| decode_compressed(&m.format, &m.data)),
        };
        if newest.is_none()
            && let Some(e) = notes.pop()
        {
            return Err(e.text);
        }
        newest.transpose()
    }
}

impl Ros2ImageSource {
    /// The newest calibration on the camera_info topic, when it differs from the last
    /// one handed on.
    fn newest_calibration(&mut self) -> Option<Result<Intrinsics, String>> {
        let (inbox, topic) = self.info.as_mut()?;
        let mut notes = Vec::new();
        let newest = match inbox.take_all("camera_info", &mut notes).pop() {
            Some(m) => super::camera_info::intrinsics(&m, topic),
            None => Err(notes.pop()?.text),
        };
        (self.calibration.as_ref() != Some(&newest)).then(|| {
            self.calibration = Some(newest.clone());
            newest
        })
    }
}

/// A sensor_msgs/Image as a frame: grey for mono8, colour otherwise.
fn raw(m: msgs::Image) -> Result<CameraImage, String> {
    let (w, h, step) = (m.width as usize, m.height as usize, m.step as usize);
    let frame = if m.encoding == "mono8" {
        GrayFrame::from_raw(w, h, &m.encoding, step, &m.data).map(CameraImage::Gray)
    } else {
        BgrFrame::from_raw(w, h, &m.encoding, step, &m.data).map(CameraImage::Colour)
    };
    frame.map_err(|e| format!("image: {e}"))
}
