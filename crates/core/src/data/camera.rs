//! What a camera pipeline made of a frame, as the console shows it.

use serde::Serialize;

/// A small grey picture of the newest frame for the console.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Thumbnail {
    pub width: usize,
    pub height: usize,
    pub pixels: Vec<u8>,
}

impl Thumbnail {
    pub fn at(&self, x: usize, y: usize) -> u8 {
        if x < self.width && y < self.height {
            self.pixels[y * self.width + x]
        } else {
            0
        }
    }
}

/// What the camera pipeline made of one frame, for the console.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CameraStatus {
    /// Every marker ID decoded, ascending.
    pub ids: Vec<u32>,
    /// Sightings passed on to the estimator.
    pub accepted: usize,
    /// Sightings refused (reprojection error or range).
    pub rejected: usize,
    /// Seconds detection took, when a stopwatch was at hand.
    pub latency: Option<f64>,
    pub thumbnail: Option<Thumbnail>,
    /// Why the frame could not be used, if it could not.
    pub error: Option<String>,
}

impl CameraStatus {
    /// A frame that could not be used, and why.
    pub fn failed(error: impl Into<String>) -> Self {
        Self {
            error: Some(error.into()),
            ..Self::default()
        }
    }
}
