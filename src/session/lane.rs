//! Lane mode's camera for a session: the twin's lane camera on a world with a track, and
//! why lane mode cannot run when there is none.

#[cfg(not(feature = "vision"))]
use super::NEEDS_VISION;
use super::{Robot, Session};
#[cfg(feature = "vision")]
use anyhow::Context;
use anyhow::{Result, bail};

impl Session {
    /// Whether the robot is the twin in a world with a lane track.
    pub fn has_track(&self) -> bool {
        matches!(&self.robot, Robot::Twin(twin) if twin.world().track.is_some())
    }

    /// Sets up lane mode's camera in a twin world with a track; when it cannot be, lane
    /// mode says why when asked for. Other worlds and robots keep lane mode's refusal.
    pub fn offer_lane_camera(
        &mut self,
        seed: u64,
        stopwatch: Option<std::sync::Arc<dyn crate::clock::Clock>>,
    ) {
        if !self.has_track() {
            return;
        }
        let lighting = crate::sim::track::Lighting::NORMAL;
        if let Err(e) = self.use_lane_camera(lighting, seed, stopwatch) {
            self.lane_unavailable = Some(format!("{e:#}"));
        }
    }

    /// Gives the twin a lane camera, when its world has a track: colour frames under
    /// `lighting` read by the OpenCV lane pipeline (lane mode, seed 000 §2-§3). Without the
    /// `vision` feature, or for a world without a track, says why lane mode cannot run.
    pub fn use_lane_camera(
        &mut self,
        lighting: crate::sim::track::Lighting,
        seed: u64,
        stopwatch: Option<std::sync::Arc<dyn crate::clock::Clock>>,
    ) -> Result<()> {
        let Robot::Twin(twin) = &mut self.robot else {
            bail!("the twin's lane camera needs the twin (--link sim)");
        };
        if twin.world().track.is_none() {
            bail!(
                "world {} has no [track]: lane mode drives a track such as maps/track.toml",
                twin.world().name
            );
        }
        #[cfg(feature = "vision")]
        {
            let lane = &self.config.lane;
            twin.use_lane_camera(&lane.camera, &lane.vision, lighting, seed, stopwatch)
                .context("cannot start the lane camera")?;
            self.lane_unavailable = None;
            Ok(())
        }
        #[cfg(not(feature = "vision"))]
        {
            let _ = (lighting, seed, stopwatch);
            bail!("lane mode {NEEDS_VISION}")
        }
    }
}
