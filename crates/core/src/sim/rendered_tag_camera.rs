//! The twin's rendered tag camera (feature `vision`): frames of a tag map's floor drawn by
//! `tag_render::TagRenderer`, each tag in OpenCV's own 36h11 pattern, read back by
//! `perception::tag_detect::TagDetector` as a real camera's would be.

use super::tag_render::TagRenderer;
use crate::clock::Clock;
use crate::geometry::Pose2;
use crate::perception::tag_camera::TagCameraConfig;
use crate::perception::tag_detect::{TagDetectError, TagDetector, TagFrame};
use crate::perception::tag_patterns::TagPatterns;
use crate::tags::{TagId, TagMap};
use rand_chacha::ChaCha8Rng;

/// One frame drawn and read, and how long each took when a stopwatch was given.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Captured {
    /// Whether the frame was drawn and read. One that shows no tag's black square whole
    /// holds nothing the detector would report (it refuses a tag with a corner within
    /// the edge margin), so it is skipped.
    pub drawn: bool,
    pub seen: TagFrame,
    /// The map's tags whose black square the frame shows whole: those to be found.
    pub in_view: Vec<TagId>,
    pub render_s: Option<f64>,
    pub detect_s: Option<f64>,
}

/// The renderer and the detector behind it.
#[derive(Debug)]
pub struct RenderedTagCamera {
    renderer: TagRenderer,
    detector: TagDetector,
    edge_margin_px: f64,
}

impl RenderedTagCamera {
    /// The camera `camera` over `map`'s floor, its tags' black squares `side` metres
    /// across; `seed` fixes the floor and the noise bank.
    pub fn new(
        map: &TagMap,
        camera: &TagCameraConfig,
        side: f64,
        seed: u64,
    ) -> Result<Self, TagDetectError> {
        let patterns = TagPatterns::new()?.all(map.tags.keys().copied());
        Ok(Self {
            renderer: TagRenderer::new(map, camera, side, &patterns, seed),
            detector: TagDetector::new(camera, side)?,
            edge_margin_px: camera.edge_margin_px,
        })
    }

    /// The image centre's floor point, metres ahead of the robot's centre.
    pub fn look(&self) -> f64 {
        self.detector.look()
    }

    /// Tags of the map that have no 36h11 pattern (ids past 586), so are not on the floor.
    pub fn unpainted(&self) -> &[TagId] {
        self.renderer.unpainted()
    }

    /// Draws the frame seen from the true pose `truth` and reads the tags of `map` in it.
    pub fn capture(
        &self,
        map: &TagMap,
        truth: Pose2,
        rng: &mut ChaCha8Rng,
        stopwatch: Option<&dyn Clock>,
    ) -> Result<Captured, TagDetectError> {
        if self.renderer.wholly_in_view(truth, 0.0).is_empty() {
            return Ok(Captured::default());
        }
        let t0 = stopwatch.map(|s| s.now());
        let frame = self.renderer.render(truth, rng);
        let t1 = stopwatch.map(|s| s.now());
        let seen = self.detector.detect(&frame, map)?;
        let t2 = stopwatch.map(|s| s.now());
        let span = |a: Option<f64>, b: Option<f64>| a.zip(b).map(|(a, b)| b - a);
        Ok(Captured {
            drawn: true,
            seen,
            in_view: self.renderer.wholly_in_view(truth, self.edge_margin_px),
            render_s: span(t0, t1),
            detect_s: span(t1, t2),
        })
    }
}
