//! A camera looking level ahead.

use navdeck::perception::config::VisionConfig;

/// A camera looking level ahead (x -90 degrees) 10 cm up, so markers up to 4 m away are
/// in frame.
pub fn level() -> VisionConfig {
    let mut v = VisionConfig::default();
    v.mount.rotation_deg = [-90.0, 0.0, -90.0];
    v.mount.translation = [0.03, 0.0, 0.10];
    v
}
