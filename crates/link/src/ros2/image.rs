//! Camera frames from a ROS 2 image topic (sensor_msgs/Image, mono8, rgb8 or bgr8) as a
//! source for the camera pipeline, on a DDS participant of its own.

use super::config::Ros2Config;
use super::participant::{Factory, Joined, join, qos_profile, take_all};
use crate::LinkError;
use navdeck_core::perception::frame::GrayFrame;
use navdeck_core::perception::pipeline::FrameSource;
use navdeck_msgs::ros as msgs;
use ros2_client::{Context, Node, Subscription};
use std::time::{Duration, Instant};

/// How long one `grab` waits for a frame.
const GRAB_WAIT: Duration = Duration::from_millis(100);

pub struct Ros2ImageSource {
    images: Subscription<msgs::Image>,
    _node: Node,
    _context: Context,
}

impl Ros2ImageSource {
    /// Subscribes to `topic` (sensor-data QoS, `[ros2] scan_qos`).
    pub fn connect(config: &Ros2Config, domain: u16, topic: &str) -> Result<Self, LinkError> {
        let Joined {
            context,
            namespace,
            mut node,
            ..
        } = join(config, domain, "navdeck_camera")?;
        let images = Factory {
            node: &mut node,
            config,
            namespace: &namespace,
        }
        .subscription(
            "camera",
            topic,
            "sensor_msgs",
            "Image",
            qos_profile(config.scan_qos, false),
        )?;
        Ok(Self {
            images,
            _node: node,
            _context: context,
        })
    }
}

impl FrameSource for Ros2ImageSource {
    fn grab(&mut self) -> Result<Option<GrayFrame>, String> {
        let give_up = Instant::now() + GRAB_WAIT;
        loop {
            let mut notes = Vec::new();
            let newest = take_all(&self.images, "image", &mut notes).pop();
            if newest.is_none()
                && let Some(e) = notes.pop()
            {
                return Err(e.text);
            }
            if let Some(m) = newest {
                return GrayFrame::from_raw(
                    m.width as usize,
                    m.height as usize,
                    &m.encoding,
                    m.step as usize,
                    &m.data,
                )
                .map(Some)
                .map_err(|e| format!("image: {e}"));
            }
            if Instant::now() >= give_up {
                return Ok(None);
            }
            // Edge of the system: the subscription has no blocking take.
            std::thread::sleep(Duration::from_millis(5));
        }
    }
}
