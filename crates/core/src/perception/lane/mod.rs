//! Lane, traffic-light and barrier perception from the lane camera's colour frames (seed
//! 000 §2-§3): lane masks in HSV held near a target pixel share by a PI loop, a bird's-eye
//! view of the floor, sliding windows and a quadratic per line, filtered over five frames;
//! lit lamps by shape and a Bayesian colour classifier; the barrier's arm by Hough segments
//! clustered into one axis, its state filtered by a discrete Bayes filter.
//!
//! The geometry, fits, filters and classifier are plain Rust; the image work (feature
//! `vision`) uses OpenCV.

pub mod arm_axis;
#[cfg(feature = "vision")]
pub mod barrier;
pub mod barrier_filter;
pub mod birdseye;
pub mod colour_bayes;
pub mod config;
pub mod lane_fit;
#[cfg(feature = "vision")]
mod light;
#[cfg(feature = "vision")]
mod masks;
#[cfg(feature = "vision")]
mod pipeline;
#[cfg(feature = "vision")]
mod shape;
#[cfg(all(test, feature = "vision"))]
mod test_frames;
#[cfg(all(test, feature = "vision"))]
mod tests;
pub mod value_loop;
pub mod windows;

#[cfg(feature = "vision")]
pub use barrier::BarrierObservation;
pub use config::{BirdsEyeView, LaneVisionConfig, LaneVisionError};
#[cfg(feature = "vision")]
pub use pipeline::{LanePipeline, ObjectDetections, THUMBNAIL};
