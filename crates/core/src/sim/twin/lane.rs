//! The twin's lane camera (feature `vision`): installed on a world with a track, it takes
//! a colour frame at its own rate and hands the lane pipeline's sighting to the next
//! frame the pilot takes.

use super::Twin;
use crate::clock::Clock;
use crate::data::LaneSighting;
use crate::perception::lane::{LaneVisionConfig, LaneVisionError};
use crate::perception::lane_camera::LaneCameraConfig;
use crate::sim::clock::SensorClock;
use crate::sim::lane_camera::LaneCamera;
use crate::sim::track::Lighting;
use std::sync::Arc;

/// The lane camera and when its frames are due.
#[derive(Clone, Debug)]
pub(super) struct LaneRig {
    camera: Box<LaneCamera>,
    clock: SensorClock,
}

impl Twin {
    /// Gives the twin a lane camera of `camera` read by a pipeline of `vision`, under
    /// `lighting` with its shadows and lamps placed by `seed`; refused when the world has
    /// no track.
    pub fn use_lane_camera(
        &mut self,
        camera: &LaneCameraConfig,
        vision: &LaneVisionConfig,
        lighting: Lighting,
        seed: u64,
        stopwatch: Option<Arc<dyn Clock>>,
    ) -> Result<(), LaneVisionError> {
        let lane = LaneCamera::new(&self.world, camera, vision, lighting, seed, stopwatch)?;
        self.sensors.lane_rig = Some(LaneRig {
            camera: Box::new(lane),
            clock: SensorClock::new(camera.rate_hz),
        });
        Ok(())
    }

    /// The lane camera, when the twin has one.
    pub fn lane_camera(&self) -> Option<&LaneCamera> {
        self.sensors.lane_rig.as_ref().map(|r| r.camera.as_ref())
    }

    pub fn lane_camera_mut(&mut self) -> Option<&mut LaneCamera> {
        self.sensors.lane_rig.as_mut().map(|r| r.camera.as_mut())
    }

    /// A lane frame when one is due at `now`: drawn and read, or dark under a camera fault.
    pub(super) fn capture_lane(&mut self, now: f64, dark: bool) {
        let pose = self.pose;
        let Some(rig) = self.sensors.lane_rig.as_mut() else {
            return;
        };
        if !rig.clock.due(now) {
            return;
        }
        let sighting = if dark {
            LaneSighting::failed("camera dark (injected fault)")
        } else {
            rig.camera.capture(pose, now, &mut self.rng)
        };
        self.sensors.lane = Some(sighting);
    }
}
