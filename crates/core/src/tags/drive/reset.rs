//! The pose from a tag seen, and the pose between tags (seed 003 §2.5 step 4, §1.2.4
//! `get_robot_pose_from_tag`, §1.2.5 `set_reference_point`).
//!
//! The seed carries the pose on from the last tag as `est = ref_robot + (odom - ref_odom)`,
//! adding the odometry's change as the odometry frame has it. That holds only while the
//! odometry's frame and the map's are turned alike; navdeck turns the change into the map
//! frame first: est = ref_robot ∘ (ref_odom⁻¹ ∘ odom), the change in the robot frame at
//! the reference carried onto the map pose there.

use super::super::file::Tag;
use crate::geometry::{Point2, Pose2, wrap_angle};
use std::f64::consts::FRAC_PI_2;

/// Sightings cross a link as data; the driver reads them here.
pub use crate::data::TagSighting;

/// The robot's pose from `sighting` of `tag`, with the camera's floor centre `look`
/// metres ahead of the robot's centre and `heading_hint` the heading believed so far
/// (it picks which quarter turn the tag's angle is taken from). Tags lie square to their
/// zone's axis: seed 003 §2.5 gives heading = zone heading + angle and, for zone A,
/// y = tag y + lateral; navdeck takes the quarter turn nearest the hint and the tag's
/// offset from the camera in both directions.
pub fn pose_from_tag(tag: &Tag, sighting: &TagSighting, look: f64, heading_hint: f64) -> Pose2 {
    let base = tag.zone.heading() + sighting.align;
    let quarters = (wrap_angle(heading_hint - base) / FRAC_PI_2).round();
    let heading = wrap_angle(base + quarters * FRAC_PI_2);
    // The tag is at (look + ahead, -lateral) in the robot frame.
    let (s, c) = heading.sin_cos();
    let (fx, fy) = (look + sighting.ahead, -sighting.lateral);
    Pose2::new(
        tag.x - (c * fx - s * fy),
        tag.y - (s * fx + c * fy),
        heading,
    )
}

/// The robot's pose with the image centre's floor point (`look` metres ahead of its
/// centre) over the map point (`x`, `y`), facing `heading`.
pub fn over_point(x: f64, y: f64, heading: f64, look: f64) -> Pose2 {
    Pose2::new(x - look * heading.cos(), y - look * heading.sin(), heading)
}

/// The map pose and the odometry's pose at the last tag: the pose now is the reference
/// carried on by the odometry's change since, turned into the map frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PoseReference {
    map: Pose2,
    odom: Pose2,
}

impl PoseReference {
    pub fn new(map: Pose2, odom: Pose2) -> Self {
        Self { map, odom }
    }

    /// The map pose with the odometry at `odom`.
    pub fn estimate(&self, odom: Pose2) -> Pose2 {
        self.map.compose(self.odom.inverse().compose(odom))
    }

    /// The map point with the odometry at `odom`.
    pub fn point(&self, odom: Pose2) -> Point2 {
        let p = self.estimate(odom);
        Point2::new(p.x, p.y)
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::file::{TagKind, Zone};
    use super::*;
    use std::f64::consts::PI;

    fn near(a: Pose2, b: Pose2) -> bool {
        (a.x - b.x).abs() < 1e-9
            && (a.y - b.y).abs() < 1e-9
            && wrap_angle(a.theta - b.theta).abs() < 1e-9
    }

    #[test]
    fn the_odometrys_change_is_turned_into_the_map_frame() {
        // At the tag the map says heading +y while the odometry says +x.
        let reference =
            PoseReference::new(Pose2::new(2.0, 1.0, PI / 2.0), Pose2::new(5.0, 5.0, 0.0));
        // One metre ahead by the odometry: one metre along +y on the map. The seed's sum
        // would put the robot at (3, 1), a metre to the side.
        let now = reference.estimate(Pose2::new(6.0, 5.0, 0.0));
        assert!(near(now, Pose2::new(2.0, 2.0, PI / 2.0)), "{now:?}");
        // A quarter turn left by the odometry faces -x on the map.
        let turned = reference.estimate(Pose2::new(5.0, 5.0, PI / 2.0));
        assert!(near(turned, Pose2::new(2.0, 1.0, PI)), "{turned:?}");
    }

    #[test]
    fn the_pose_from_a_tag_follows_the_seed_in_zone_a_and_turns_with_the_zone() {
        let tag = |zone| Tag {
            x: 3.0,
            y: 1.0,
            kind: TagKind::Waypoint,
            zone,
        };
        // Zone A, camera over the robot's centre, tag 0.02 m right: seed 003 §2.5,
        // x = tag x, y = tag y + lateral, heading = the angle; navdeck turns the offset
        // by the heading, which the seed's form leaves out (its small-angle case).
        let s = TagSighting {
            id: 101,
            ahead: 0.0,
            lateral: 0.02,
            align: 0.01,
        };
        let p = pose_from_tag(&tag(Zone::A), &s, 0.0, 0.0);
        let (sin, cos) = 0.01f64.sin_cos();
        assert!(
            near(p, Pose2::new(3.0 - 0.02 * sin, 1.0 + 0.02 * cos, 0.01)),
            "{p:?}"
        );
        let square = pose_from_tag(&tag(Zone::A), &TagSighting { align: 0.0, ..s }, 0.0, 0.0);
        assert!(near(square, Pose2::new(3.0, 1.02, 0.0)), "{square:?}");
        // Zone B faces +y: x = tag x - lateral.
        let p = pose_from_tag(&tag(Zone::B), &TagSighting { align: 0.0, ..s }, 0.0, 1.5);
        assert!(near(p, Pose2::new(2.98, 1.0, PI / 2.0)), "{p:?}");
        // The camera 0.1 m ahead of the centre and the tag 0.05 m past the image centre:
        // the robot's centre is 0.15 m short of the tag along its heading.
        let p = pose_from_tag(
            &tag(Zone::A),
            &TagSighting {
                ahead: 0.05,
                lateral: 0.0,
                align: 0.0,
                ..s
            },
            0.1,
            0.0,
        );
        assert!(near(p, Pose2::new(2.85, 1.0, 0.0)), "{p:?}");
        // Driving back out of zone A the robot faces -x: the hint picks the half turn.
        let p = pose_from_tag(&tag(Zone::A), &TagSighting { align: 0.0, ..s }, 0.0, 3.0);
        assert!((p.theta.abs() - PI).abs() < 1e-9, "{p:?}");
    }
}
