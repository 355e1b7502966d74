//! The twin's ideal tag camera (seed 003 §2.1's outputs without the image): every tag of
//! a tag map lying in the camera's view of the floor is reported with its offset from
//! the image centre's floor point and its angle, from the true pose, with a little noise
//! drawn from the caller's generator.

use crate::geometry::{Point2, Pose2, wrap_angle};
use crate::tags::drive::TagSighting;
use crate::tags::{Tag, TagId, TagMap};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use std::f64::consts::FRAC_PI_2;

/// Where the camera looks and how well it measures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TagCamera {
    /// The image centre's floor point, metres ahead of the robot's centre.
    pub look: f64,
    /// Half the view's length along the heading and half its width, metres.
    pub half_length: f64,
    pub half_width: f64,
    /// Standard deviations of the offsets (m) and the angle (rad).
    pub offset_sd: f64,
    pub angle_sd: f64,
}

impl Default for TagCamera {
    fn default() -> Self {
        Self {
            look: 0.1,
            half_length: 0.15,
            half_width: 0.2,
            offset_sd: 0.002,
            angle_sd: 0.2f64.to_radians(),
        }
    }
}

impl TagCamera {
    /// The image centre's floor point with the robot at `pose`.
    pub fn centre(&self, pose: Pose2) -> Point2 {
        let (s, c) = pose.theta.sin_cos();
        Point2::new(pose.x + self.look * c, pose.y + self.look * s)
    }

    /// Tag `id` lying at `tag` as seen from the true pose `truth` without noise,
    /// wherever it lies.
    pub fn exact(&self, id: TagId, tag: &Tag, truth: Pose2) -> TagSighting {
        let (s, c) = truth.theta.sin_cos();
        let centre = self.centre(truth);
        let (dx, dy) = (tag.x - centre.x, tag.y - centre.y);
        let (ahead, left) = (c * dx + s * dy, -s * dx + c * dy);
        // A square tag looks alike a quarter turned: the angle folds into ±45°.
        let turned = wrap_angle(truth.theta - tag.zone.heading());
        let align = turned - (turned / FRAC_PI_2).round() * FRAC_PI_2;
        TagSighting {
            id,
            ahead,
            lateral: -left,
            align,
        }
    }

    /// The tags of `map` in view from the true pose `truth`.
    pub fn sightings(&self, map: &TagMap, truth: Pose2, rng: &mut ChaCha8Rng) -> Vec<TagSighting> {
        let offset = Normal::new(0.0, self.offset_sd.max(0.0)).ok();
        let angle = Normal::new(0.0, self.angle_sd.max(0.0)).ok();
        let noise = |n: Option<Normal<f64>>, rng: &mut ChaCha8Rng| n.map_or(0.0, |n| n.sample(rng));
        let mut seen = Vec::new();
        for (&id, tag) in &map.tags {
            let exact = self.exact(id, tag, truth);
            if exact.ahead.abs() > self.half_length || exact.lateral.abs() > self.half_width {
                continue;
            }
            seen.push(TagSighting {
                id,
                ahead: exact.ahead + noise(offset, rng),
                lateral: exact.lateral + noise(offset, rng),
                align: exact.align + noise(angle, rng),
            });
        }
        seen
    }
}
