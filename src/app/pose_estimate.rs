//! RViz's "2D Pose Estimate" by keyboard: the first press takes the goal cursor as the
//! robot's position, the second takes the cursor's direction from there as its heading,
//! and the pilot places the estimate (MCL's particles, or the EKF's pose) there.

use super::App;
use crate::data::Level;
use crate::geometry::Pose2;
use crate::pilot;

/// The cursor must move at least this far from the position to give a heading, metres;
/// closer, the heading stays the estimate's.
const LEAST_ARROW: f64 = 1e-6;

impl App {
    pub(super) fn pose_estimate_key(&mut self) {
        let cursor = self
            .cursor
            .unwrap_or_else(|| self.pilot().estimated_pose().position());
        match self.pose_anchor.take() {
            None => {
                self.pose_anchor = Some(cursor);
                self.log(
                    Level::Info,
                    format!(
                        "pose estimate at ({:.2}, {:.2}): move the cursor the way the robot faces and press the key again",
                        cursor.x, cursor.y
                    ),
                );
            }
            Some(at) => {
                let (dx, dy) = (cursor.x - at.x, cursor.y - at.y);
                let theta = if dx.hypot(dy) > LEAST_ARROW {
                    dy.atan2(dx)
                } else {
                    self.pilot().estimated_pose().theta
                };
                self.cursor = Some(at);
                self.run_intent(pilot::Intent::SetPose(Pose2::new(at.x, at.y, theta)));
            }
        }
    }

    /// Where a pose estimate's position was placed, waiting for its heading.
    pub fn pose_anchor(&self) -> Option<crate::geometry::Point2> {
        self.pose_anchor
    }
}
