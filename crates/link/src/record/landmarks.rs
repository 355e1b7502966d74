//! Landmarks in a recording: one flat CYLINDER marker each, its scale the 95 % ellipse's
//! full axes and its yaw the major axis, so RViz and Foxglove draw the ellipse and a
//! replay gets the covariance back. (The live RViz display draws outlines instead, which
//! cost ten times the bytes.)

use nalgebra::Matrix2;
use navdeck_core::geometry::{Point2, Pose2};
use navdeck_core::slam::ekf::LandmarkEstimate;
use navdeck_core::slam::ellipse::{CHI2_2DOF_95, axes};
use navdeck_msgs::picture::{color_of, pose};
use navdeck_msgs::ros::{self as msgs, Header, MarkerHumble, Time, Vector3};

/// visualization_msgs/Marker CYLINDER.
const CYLINDER: i32 = 3;
/// Height of the drawn disc, metres.
const DISC: f64 = 0.005;

/// A DELETEALL (landmarks gone since drop out), then one disc per landmark.
pub fn markers(list: &[LandmarkEstimate], stamp: Time, frame: &str) -> Vec<MarkerHumble> {
    let header = Header::new(stamp, frame);
    let mut out = vec![MarkerHumble {
        header: header.clone(),
        action: msgs::MARKER_DELETEALL,
        ..Default::default()
    }];
    out.extend(list.iter().map(|l| {
        let (major, minor, angle) = axes(&l.covariance, CHI2_2DOF_95);
        MarkerHumble {
            header: header.clone(),
            ns: "landmarks".into(),
            id: l.id as i32,
            kind: CYLINDER,
            action: msgs::MARKER_ADD,
            pose: pose(Pose2::new(l.mean.x, l.mean.y, angle)),
            scale: Vector3 {
                x: 2.0 * major,
                y: 2.0 * minor,
                z: DISC,
            },
            color: color_of(l.id),
            ..Default::default()
        }
    }));
    out
}

/// The landmarks `markers` wrote: mean and covariance back from each disc (the
/// sightings count is not recorded).
pub fn from_markers(list: &[MarkerHumble]) -> Vec<LandmarkEstimate> {
    list.iter()
        .filter(|m| m.kind == CYLINDER && m.action == msgs::MARKER_ADD && m.id >= 0)
        .map(|m| {
            // Σ = R diag(λ1, λ2) Rᵀ with λ = (semi-axis)² / χ² (inverse of `axes`).
            let (l1, l2) = (
                (0.5 * m.scale.x).powi(2) / CHI2_2DOF_95,
                (0.5 * m.scale.y).powi(2) / CHI2_2DOF_95,
            );
            let (s, c) = m.pose.orientation.yaw().sin_cos();
            let r = Matrix2::new(c, -s, s, c);
            LandmarkEstimate {
                id: m.id as u32,
                mean: Point2::new(m.pose.position.x, m.pose.position.y),
                covariance: r * Matrix2::new(l1, 0.0, 0.0, l2) * r.transpose(),
                sightings: 0,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_landmark_comes_back_from_its_disc() {
        let l = LandmarkEstimate {
            id: 12,
            mean: Point2::new(1.5, -0.25),
            covariance: Matrix2::new(4e-4, 1e-4, 1e-4, 2e-4),
            sightings: 9,
        };
        let back = from_markers(&markers(std::slice::from_ref(&l), Time::default(), "map"));
        assert_eq!(back.len(), 1);
        assert_eq!(back[0].id, 12);
        assert!(back[0].mean.distance(l.mean) < 1e-12);
        assert!((back[0].covariance - l.covariance).abs().max() < 1e-12);
    }
}
