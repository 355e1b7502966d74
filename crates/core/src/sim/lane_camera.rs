//! The twin's lane camera (feature `vision`): colour frames of the track drawn by
//! `track_render::TrackRenderer`, read by the OpenCV lane pipeline like a real camera's.

use super::World;
use super::track::Lighting;
use super::track_render::TrackRenderer;
use crate::clock::Clock;
use crate::data::LaneSighting;
use crate::geometry::Pose2;
use crate::perception::lane::{LanePipeline, LaneVisionConfig, LaneVisionError};
use crate::perception::lane_camera::LaneCameraConfig;
use rand_chacha::ChaCha8Rng;
use std::sync::Arc;

/// The renderer and the pipeline behind it.
pub struct LaneCamera {
    renderer: TrackRenderer,
    pipeline: LanePipeline,
    /// What the pipeline was built from, to build a clone's.
    built: (LaneVisionConfig, LaneCameraConfig),
    stopwatch: Option<Arc<dyn Clock>>,
}

impl Clone for LaneCamera {
    /// A clone draws the same frames; its pipeline starts afresh (its temporal filters and
    /// OpenCV buffers are not copied), as a camera restarted.
    fn clone(&self) -> Self {
        let (vision, camera) = &self.built;
        Self {
            renderer: self.renderer.clone(),
            pipeline: LanePipeline::new(vision, camera).expect("built once from the same config"),
            built: self.built.clone(),
            stopwatch: self.stopwatch.clone(),
        }
    }
}

impl std::fmt::Debug for LaneCamera {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LaneCamera").finish_non_exhaustive()
    }
}

impl LaneCamera {
    /// The lane camera of `camera` in `world` (which must have a track) under
    /// `lighting`, its shadows and lamps placed by `seed`.
    pub fn new(
        world: &World,
        camera: &LaneCameraConfig,
        vision: &LaneVisionConfig,
        lighting: Lighting,
        seed: u64,
        stopwatch: Option<Arc<dyn Clock>>,
    ) -> Result<Self, LaneVisionError> {
        let scene = world.track.as_ref().ok_or_else(|| {
            LaneVisionError::Setup(format!("world {} has no [track]", world.name))
        })?;
        let boxes: Vec<(Pose2, f64, f64)> = (world.obstacles.iter())
            .map(|o| (o.pose, o.width, o.height))
            .collect();
        Ok(Self {
            renderer: TrackRenderer::new(scene, &world.walls, &boxes, camera, lighting, seed),
            pipeline: LanePipeline::new(vision, camera)?,
            built: (vision.clone(), camera.clone()),
            stopwatch,
        })
    }

    /// Draws the frame seen from `pose` at twin time `t` and reads it.
    pub fn capture(&mut self, pose: Pose2, t: f64, rng: &mut ChaCha8Rng) -> LaneSighting {
        let frame = self.renderer.render(pose, t, rng);
        self.pipeline.read(&frame, self.stopwatch.as_deref())
    }
}
