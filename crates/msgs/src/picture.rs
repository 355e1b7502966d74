//! navdeck's picture as ROS 2 messages for RViz: the map, the plan, the landmarks with
//! their covariance ellipses, the estimated pose, MCL's particles and the map -> odom
//! transform.

use crate::ros::{self as msgs, ColorRgba, Header, MarkerHumble, Quaternion, Time, Vector3};
use nalgebra::Matrix3;
use navdeck_core::geometry::{Point2, Pose2, wrap_angle};
use navdeck_core::map::grid::OccupancyGrid;
use navdeck_core::perception::markers::MarkerCategory;
use navdeck_core::slam::ekf::LandmarkEstimate;
use navdeck_core::slam::ellipse::{CHI2_2DOF_95, outline};

/// Points on each landmark's ellipse outline.
const ELLIPSE_POINTS: usize = 24;

/// Particles in one /particlecloud message at most (AMCL's default max_particles is
/// 2000): about 280 kB, so a large filter does not flood the network.
pub const MAX_CLOUD_POSES: usize = 5000;

fn point(p: Point2) -> Vector3 {
    Vector3 {
        x: p.x,
        y: p.y,
        z: 0.0,
    }
}

/// A planar pose as geometry_msgs/Pose.
pub fn pose(p: Pose2) -> msgs::Pose {
    msgs::Pose {
        position: point(p.position()),
        orientation: Quaternion::from_yaw(p.theta),
    }
}

/// The estimated pose with its 3x3 (x, y, θ) covariance placed in ROS's 6x6 (x, y, z,
/// roll, pitch, yaw) layout; the unobserved z, roll and pitch get a large variance.
pub fn pose_with_covariance(
    p: Pose2,
    cov: &Matrix3<f64>,
    stamp: Time,
    frame: &str,
) -> msgs::PoseWithCovarianceStamped {
    let mut c = [0.0; 36];
    let slots = [0, 1, 5];
    for (i, &ri) in slots.iter().enumerate() {
        for (j, &cj) in slots.iter().enumerate() {
            c[ri * 6 + cj] = cov[(i, j)];
        }
    }
    for k in [2, 3, 4] {
        c[k * 6 + k] = 1e6;
    }
    msgs::PoseWithCovarianceStamped {
        header: Header::new(stamp, frame),
        pose: msgs::PoseWithCovariance {
            pose: pose(p),
            covariance: msgs::Covariance6(c),
        },
    }
}

/// MCL's particles as geometry_msgs/PoseArray, as AMCL publishes them; a larger filter
/// is thinned to MAX_CLOUD_POSES evenly spread through the list.
pub fn particle_cloud(particles: &[Pose2], stamp: Time, frame: &str) -> msgs::PoseArray {
    let n = particles.len();
    let shown = n.min(MAX_CLOUD_POSES);
    msgs::PoseArray {
        header: Header::new(stamp, frame),
        poses: (0..shown).map(|i| pose(particles[i * n / shown])).collect(),
    }
}

/// The map -> odom transform that puts the robot where navdeck believes it is, given
/// where the robot's odometry puts it: T_map_odom = T_map_base · T_odom_base⁻¹ (REP 105).
pub fn map_to_odom(in_map: Pose2, in_odom: Pose2) -> Pose2 {
    let theta = wrap_angle(in_map.theta - in_odom.theta);
    let (s, c) = theta.sin_cos();
    Pose2::new(
        in_map.x - (c * in_odom.x - s * in_odom.y),
        in_map.y - (s * in_odom.x + c * in_odom.y),
        theta,
    )
}

pub fn transform(parent: &str, child: &str, t: Pose2, stamp: Time) -> msgs::TfMessage {
    msgs::TfMessage {
        transforms: vec![msgs::TransformStamped {
            header: Header::new(stamp, parent),
            child_frame_id: child.to_string(),
            transform: msgs::Transform {
                translation: point(t.position()),
                rotation: Quaternion::from_yaw(t.theta),
            },
        }],
    }
}

/// The planned path as nav_msgs/Path, each pose facing along the path.
pub fn path(points: &[Point2], stamp: Time, frame: &str) -> msgs::Path {
    let poses = points
        .iter()
        .enumerate()
        .map(|(i, &p)| {
            let next = points.get(i + 1).or(i.checked_sub(1).map(|j| &points[j]));
            let heading = match next {
                Some(&q) if i + 1 < points.len() => (q.y - p.y).atan2(q.x - p.x),
                Some(&q) => (p.y - q.y).atan2(p.x - q.x),
                None => 0.0,
            };
            msgs::PoseStamped {
                header: Header::new(stamp, frame),
                pose: pose(Pose2::new(p.x, p.y, heading)),
            }
        })
        .collect();
    msgs::Path {
        header: Header::new(stamp, frame),
        poses,
    }
}

/// The sensed occupancy grid as nav_msgs/OccupancyGrid (the same cell layout).
pub fn grid(g: &OccupancyGrid, stamp: Time, frame: &str) -> msgs::OccupancyGrid {
    msgs::OccupancyGrid {
        header: Header::new(stamp, frame),
        info: msgs::MapMetaData {
            map_load_time: stamp,
            resolution: g.resolution as f32,
            width: g.width as u32,
            height: g.height as u32,
            origin: pose(Pose2::new(g.origin.x, g.origin.y, 0.0)),
        },
        data: msgs::Cells(g.cells.clone()),
    }
}

pub fn color_of(id: u32) -> ColorRgba {
    let (r, g, b) = match MarkerCategory::of(id) {
        MarkerCategory::Boundary => (0.6, 0.6, 0.6),
        MarkerCategory::Obstacle => (1.0, 0.5, 0.0),
        MarkerCategory::RedGate | MarkerCategory::RedBlock => (1.0, 0.1, 0.1),
        MarkerCategory::BlueGate | MarkerCategory::BlueBlock => (0.2, 0.4, 1.0),
        MarkerCategory::Unknown => (0.8, 0.8, 0.2),
    };
    ColorRgba { r, g, b, a: 1.0 }
}

/// One landmark per pair of markers: its 95 % ellipse as a closed line strip, and its
/// ID as text; a DELETEALL first clears landmarks that are gone.
pub fn landmarks(list: &[LandmarkEstimate], stamp: Time, frame: &str) -> Vec<MarkerHumble> {
    let header = Header::new(stamp, frame);
    let mut out = vec![MarkerHumble {
        header: header.clone(),
        action: msgs::MARKER_DELETEALL,
        ..Default::default()
    }];
    for l in list {
        let mut ring: Vec<Vector3> = outline(l.mean, &l.covariance, CHI2_2DOF_95, ELLIPSE_POINTS)
            .into_iter()
            .map(point)
            .collect();
        ring.push(ring[0]);
        out.push(MarkerHumble {
            header: header.clone(),
            ns: "ellipses".into(),
            id: l.id as i32,
            kind: msgs::MARKER_LINE_STRIP,
            action: msgs::MARKER_ADD,
            pose: msgs::Pose::default(),
            scale: Vector3 {
                x: 0.01,
                ..Default::default()
            },
            color: color_of(l.id),
            points: ring,
            ..Default::default()
        });
        out.push(MarkerHumble {
            header: header.clone(),
            ns: "ids".into(),
            id: l.id as i32,
            kind: msgs::MARKER_TEXT_VIEW_FACING,
            action: msgs::MARKER_ADD,
            pose: pose(Pose2::new(l.mean.x, l.mean.y, 0.0)),
            scale: Vector3 {
                z: 0.08,
                ..Default::default()
            },
            color: color_of(l.id),
            text: l.id.to_string(),
            ..Default::default()
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Matrix2;

    #[test]
    fn map_to_odom_composes_back_to_the_map_pose() {
        let in_map = Pose2::new(1.0, 2.0, 0.5);
        let in_odom = Pose2::new(0.3, -0.2, -0.4);
        let t = map_to_odom(in_map, in_odom);
        // T_map_odom · T_odom_base = T_map_base.
        let p = t.transform_point(in_odom.position());
        assert!((p.x - 1.0).abs() < 1e-12 && (p.y - 2.0).abs() < 1e-12);
        assert!((wrap_angle(t.theta + in_odom.theta) - 0.5).abs() < 1e-12);
    }

    #[test]
    fn the_pose_covariance_lands_in_the_x_y_yaw_slots() {
        let cov = Matrix3::new(1.0, 2.0, 3.0, 2.0, 4.0, 5.0, 3.0, 5.0, 6.0);
        let m = pose_with_covariance(Pose2::default(), &cov, Time::default(), "map");
        let c = m.pose.covariance.0;
        assert_eq!(
            (c[0], c[1], c[5], c[7], c[11], c[35]),
            (1.0, 2.0, 3.0, 4.0, 5.0, 6.0)
        );
        assert_eq!(c[30], 3.0);
    }

    #[test]
    fn particles_become_poses_and_a_large_cloud_is_thinned_evenly() {
        let few = [Pose2::new(1.0, 2.0, 0.5), Pose2::new(-1.0, 0.0, -3.0)];
        let m = particle_cloud(&few, Time::default(), "map");
        assert_eq!(m.header.frame_id, "map");
        assert_eq!(m.poses.len(), 2);
        assert_eq!((m.poses[0].position.x, m.poses[0].position.y), (1.0, 2.0));
        assert!((m.poses[1].orientation.yaw() + 3.0).abs() < 1e-12);
        let many: Vec<Pose2> = (0..12_000)
            .map(|i| Pose2::new(f64::from(i), 0.0, 0.0))
            .collect();
        let m = particle_cloud(&many, Time::default(), "map");
        assert_eq!(m.poses.len(), MAX_CLOUD_POSES);
        // Pose i is particle ⌊2.4 i⌋: 0, 2, 4, 7, ... up to 11 997 of 0..=11 999.
        let xs = |i: usize| m.poses[i].position.x;
        assert_eq!((xs(0), xs(1), xs(2), xs(3)), (0.0, 2.0, 4.0, 7.0));
        assert_eq!(xs(MAX_CLOUD_POSES - 1), 11_997.0);
        assert!(particle_cloud(&[], Time::default(), "map").poses.is_empty());
    }

    #[test]
    fn each_landmark_becomes_a_closed_ellipse_and_a_label() {
        let l = LandmarkEstimate {
            id: 7,
            mean: Point2::new(1.0, 1.0),
            covariance: Matrix2::new(0.01, 0.0, 0.0, 0.0025),
            sightings: 3,
        };
        let m = landmarks(&[l], Time::default(), "map");
        assert_eq!(m.len(), 3);
        assert_eq!(m[0].action, msgs::MARKER_DELETEALL);
        let ring = &m[1].points;
        assert_eq!(ring.first(), ring.last());
        // 95 % semi-major axis: sqrt(5.991 x 0.01) = 0.245 m.
        let reach = ring
            .iter()
            .map(|p| (p.x - 1.0).hypot(p.y - 1.0))
            .fold(0.0, f64::max);
        assert!((reach - (CHI2_2DOF_95 * 0.01f64).sqrt()).abs() < 1e-9);
        assert_eq!(m[2].text, "7");
    }
}
