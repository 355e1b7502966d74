//! The twin's rendered camera (feature `vision`): frames drawn by `render::Renderer`,
//! read by the ArUco detector like a real camera's.
//!
//! Frames are drawn whole (for the console's camera panel) or only where the detector
//! could accept a sighting (`CameraFrames::Readable`): the same sightings for a fraction
//! of the work.

pub use super::render::Renderer;
use super::{CameraFrames, Marker};
use crate::clock::Clock;
use crate::data::MarkerSighting;
use crate::geometry::{Pose2, Segment};
use crate::perception::aruco::{Detector, VisionError};
use crate::perception::config::VisionConfig;
use crate::perception::frame::{CameraStatus, GrayFrame};
use rand_chacha::ChaCha8Rng;

/// The twin's camera with the ArUco detector behind it: frames in, sightings out.
#[derive(Clone)]
pub struct RenderedCamera {
    renderer: Renderer,
    detector: Detector,
    stopwatch: Option<std::sync::Arc<dyn Clock>>,
    frames: CameraFrames,
    /// The frame readable renders draw into, kept from one frame to the next.
    canvas: GrayFrame,
}

impl std::fmt::Debug for RenderedCamera {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RenderedCamera")
            .field("detector", &self.detector)
            .finish_non_exhaustive()
    }
}

impl RenderedCamera {
    /// The camera of `vision.render.mount` (not the real robot's `vision.mount`), whose
    /// sightings end at `max_range` metres or the detector's own limit if nearer.
    pub fn new(
        vision: &VisionConfig,
        max_range: f64,
        stopwatch: Option<std::sync::Arc<dyn Clock>>,
    ) -> Result<Self, VisionError> {
        let mut twin = vision.clone();
        twin.mount = vision.render.mount.clone();
        twin.detector.max_range = twin.detector.max_range.min(max_range);
        let detector = Detector::from_config(&twin)?;
        let k = detector.intrinsics();
        Ok(Self {
            renderer: Renderer::new(&vision.markers, &vision.render),
            canvas: GrayFrame::filled(k.width as usize, k.height as usize, 0),
            detector,
            stopwatch,
            frames: CameraFrames::Whole,
        })
    }

    /// Draws `frames` from now on.
    pub fn set_frames(&mut self, frames: CameraFrames) {
        self.frames = frames;
    }

    /// The detector reading this camera's frames, with its mount and intrinsics.
    pub fn detector(&self) -> &Detector {
        &self.detector
    }

    /// Renders the frame seen from `pose`, detects its markers and reports both.
    pub fn capture<'a>(
        &mut self,
        pose: Pose2,
        markers: impl IntoIterator<Item = &'a Marker>,
        occluders: &[&[Segment]],
        rng: &mut ChaCha8Rng,
    ) -> (Vec<MarkerSighting>, CameraStatus) {
        if self.frames == CameraFrames::Readable {
            return self.capture_readable(pose, markers, occluders, rng);
        }
        let frame = match self
            .renderer
            .render(&self.detector, pose, markers, occluders, rng)
        {
            Ok(f) => f,
            Err(e) => return (Vec::new(), CameraStatus::failed(e.to_string())),
        };
        self.detector.read(&frame, self.stopwatch.as_deref())
    }

    /// `capture` drawing and detecting only where a sighting could be accepted; a frame
    /// with no such place is not drawn or detected at all.
    fn capture_readable<'a>(
        &mut self,
        pose: Pose2,
        markers: impl IntoIterator<Item = &'a Marker>,
        occluders: &[&[Segment]],
        rng: &mut ChaCha8Rng,
    ) -> (Vec<MarkerSighting>, CameraStatus) {
        let drawn = self.renderer.render_readable(
            &self.detector,
            pose,
            markers,
            occluders,
            rng,
            &mut self.canvas,
        );
        let detected = drawn.map_err(VisionError::from).and_then(|windows| {
            if windows.is_empty() {
                return Ok(Default::default());
            }
            self.detector
                .detect_in(&self.canvas, &windows, self.stopwatch.as_deref())
        });
        match detected {
            Ok(d) => (d.marker_sightings(), d.status(None)),
            Err(e) => (Vec::new(), CameraStatus::failed(e.to_string())),
        }
    }
}
