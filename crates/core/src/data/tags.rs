//! A floor tag seen by the camera (seed 003 §2.1's lateral, distance and corner angle),
//! as it crosses a link in `SensorFrame::tags`.

use serde::{Deserialize, Serialize};

/// A tag as the camera sees it, relative to the point of the floor at the image's centre
/// (seed 003 §2.1: lateral, distance, the corners' angle).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct TagSighting {
    /// The tag's id (AprilTag 36h11; a tag map's key).
    pub id: u32,
    /// Metres the tag lies ahead of the image centre's floor point.
    pub ahead: f64,
    /// Metres the tag lies to the right of it (the seed's sign: + right).
    pub lateral: f64,
    /// The tag's top edge's angle in the image, radians, + anticlockwise, folded into
    /// ±45° (a square tag looks alike turned a quarter).
    pub align: f64,
}
