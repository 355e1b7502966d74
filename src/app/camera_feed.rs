//! What the camera pipeline reported, for the camera panel: the newest frame's status and
//! the frame rate.

use super::App;
use crate::perception::frame::CameraStatus;

#[derive(Clone, Debug, Default)]
pub struct CameraFeed {
    pub status: Option<CameraStatus>,
    pub frames: u64,
    /// Frames per second, smoothed.
    pub rate: f64,
    last_at: Option<f64>,
}

impl App {
    pub(super) fn note_camera(&mut self, t: f64, status: CameraStatus) {
        let feed = &mut self.camera;
        if let Some(last) = feed.last_at
            && t > last
        {
            let instant = 1.0 / (t - last);
            // Exponential smoothing over about five frames.
            feed.rate = if feed.frames < 2 {
                instant
            } else {
                feed.rate + 0.2 * (instant - feed.rate)
            };
        }
        feed.last_at = Some(t);
        feed.frames += 1;
        feed.status = Some(status);
    }

    /// The camera pipeline's newest report, if a camera is detected in navdeck.
    pub fn camera(&self) -> &CameraFeed {
        &self.camera
    }
}
