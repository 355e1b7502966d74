//! RViz's "2D Pose Estimate" (geometry_msgs/PoseWithCovarianceStamped on /initialpose,
//! checked before it places navdeck's estimate, as Nav2's AMCL reads it) and "2D Goal
//! Pose" (geometry_msgs/PoseStamped on /goal_pose). A pose that is not finite, has no
//! rotation, or is in another frame is refused, naming the value.

use navdeck_core::data::frame_check::MAX_COORDINATE;
use navdeck_core::data::number::short;
use navdeck_core::geometry::Pose2;
use navdeck_msgs::ros as msgs;

/// Why a pose from RViz (/initialpose, /goal_pose) was not applied.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum BadPose {
    #[error("header.frame_id = {found:?}, expected {expected:?} (or empty)")]
    Frame { found: String, expected: String },
    #[error("{field} = {value} is not finite")]
    NonFinite { field: String, value: f64 },
    #[error(
        "{field} = {} m is over {} m from the map's origin",
        short(*value),
        short(MAX_COORDINATE)
    )]
    Far { field: String, value: f64 },
    #[error("{path}orientation = (x {x}, y {y}, z {z}, w {w}) is a zero quaternion")]
    ZeroQuaternion {
        path: &'static str,
        x: f64,
        y: f64,
        z: f64,
        w: f64,
    },
}

/// The planar pose in an /initialpose message, which must be in `map_frame` (an empty
/// frame_id counts as the map, as some RViz set-ups send it).
pub fn initial_pose(
    msg: &msgs::PoseWithCovarianceStamped,
    map_frame: &str,
) -> Result<Pose2, BadPose> {
    planar_pose(&msg.header, &msg.pose.pose, map_frame, "pose.pose.")
}

/// The planar pose in a /goal_pose message (RViz's "2D Goal Pose"), checked the same way.
pub fn goal_pose(msg: &msgs::PoseStamped, map_frame: &str) -> Result<Pose2, BadPose> {
    planar_pose(&msg.header, &msg.pose, map_frame, "pose.")
}

/// `pose` under `header` as x, y and yaw in `map_frame`; `path` is where the pose sits in
/// its message, for the refusal's wording.
fn planar_pose(
    header: &msgs::Header,
    pose: &msgs::Pose,
    map_frame: &str,
    path: &'static str,
) -> Result<Pose2, BadPose> {
    let frame = header.frame_id.as_str();
    if !frame.is_empty() && frame != map_frame {
        return Err(BadPose::Frame {
            found: frame.to_string(),
            expected: map_frame.to_string(),
        });
    }
    let p = pose.position;
    let q = pose.orientation;
    let values = [
        ("position.x", p.x),
        ("position.y", p.y),
        ("position.z", p.z),
        ("orientation.x", q.x),
        ("orientation.y", q.y),
        ("orientation.z", q.z),
        ("orientation.w", q.w),
    ];
    if let Some(&(field, value)) = values.iter().find(|(_, v)| !v.is_finite()) {
        return Err(BadPose::NonFinite {
            field: format!("{path}{field}"),
            value,
        });
    }
    if let Some(&(field, value)) = values[..2].iter().find(|(_, v)| v.abs() > MAX_COORDINATE) {
        return Err(BadPose::Far {
            field: format!("{path}{field}"),
            value,
        });
    }
    let unit = unit(q).ok_or(BadPose::ZeroQuaternion {
        path,
        x: q.x,
        y: q.y,
        z: q.z,
        w: q.w,
    })?;
    Ok(Pose2::new(p.x, p.y, unit.yaw()))
}

/// q / |q|, or None for the zero quaternion: the yaw formula in `Quaternion::yaw` holds
/// for unit quaternions only (tf2::getYaw, which AMCL applies to /initialpose, divides
/// by |q|² the same way). Scaled by the largest component first so that neither tiny
/// nor huge finite components underflow or overflow.
fn unit(q: msgs::Quaternion) -> Option<msgs::Quaternion> {
    let c = [q.x, q.y, q.z, q.w];
    let largest = c.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if largest == 0.0 {
        return None;
    }
    let [x, y, z, w] = c.map(|v| v / largest);
    let norm = (x * x + y * y + z * z + w * w).sqrt();
    Some(msgs::Quaternion {
        x: x / norm,
        y: y / norm,
        z: z / norm,
        w: w / norm,
    })
}

/// The newest acceptable pose among `messages` (oldest first), and what was wrong with
/// each refused one, in order.
pub fn newest<M>(
    messages: &[M],
    map_frame: &str,
    read: fn(&M, &str) -> Result<Pose2, BadPose>,
) -> (Option<Pose2>, Vec<BadPose>) {
    let mut pose = None;
    let mut refused = Vec::new();
    for msg in messages {
        match read(msg, map_frame) {
            Ok(p) => pose = Some(p),
            Err(why) => refused.push(why),
        }
    }
    (pose, refused)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn estimate(
        frame: &str,
        x: f64,
        y: f64,
        q: msgs::Quaternion,
    ) -> msgs::PoseWithCovarianceStamped {
        let mut m = msgs::PoseWithCovarianceStamped {
            header: msgs::Header::new(msgs::Time::default(), frame),
            ..Default::default()
        };
        m.pose.pose.position.x = x;
        m.pose.pose.position.y = y;
        m.pose.pose.orientation = q;
        m
    }

    #[test]
    fn a_pose_in_the_map_frame_gives_its_position_and_yaw() {
        let p = initial_pose(
            &estimate("map", 1.5, -2.0, msgs::Quaternion::from_yaw(2.0)),
            "map",
        )
        .unwrap();
        assert!((p.x - 1.5).abs() < 1e-12 && (p.y + 2.0).abs() < 1e-12);
        assert!((p.theta - 2.0).abs() < 1e-12, "{}", p.theta);
        // An empty frame counts as the map.
        assert!(initial_pose(&estimate("", 0.0, 0.0, Default::default()), "map").is_ok());
    }

    #[test]
    fn a_quaternion_of_any_length_gives_the_same_yaw() {
        // (0, 0, sin 45°, cos 45°) scaled by 3, and by 1e-200: a quarter turn either way.
        let s = std::f64::consts::FRAC_1_SQRT_2;
        for k in [3.0, 1e-200, 1e200] {
            let q = msgs::Quaternion {
                x: 0.0,
                y: 0.0,
                z: k * s,
                w: k * s,
            };
            let p = initial_pose(&estimate("map", 0.0, 0.0, q), "map").unwrap();
            assert!(
                (p.theta - std::f64::consts::FRAC_PI_2).abs() < 1e-12,
                "{k}: {}",
                p.theta
            );
        }
    }

    #[test]
    fn other_frames_non_finite_values_and_zero_quaternions_are_refused_by_name() {
        let odom = initial_pose(&estimate("odom", 1.0, 0.0, Default::default()), "map");
        let err = odom.unwrap_err().to_string();
        assert!(
            err.contains("frame_id") && err.contains("\"odom\""),
            "{err}"
        );
        let nan = initial_pose(&estimate("map", f64::NAN, 0.0, Default::default()), "map");
        assert_eq!(
            nan.clone().unwrap_err().to_string(),
            "pose.pose.position.x = NaN is not finite"
        );
        let mut q = msgs::Quaternion::from_yaw(0.0);
        q.w = f64::INFINITY;
        let inf = initial_pose(&estimate("map", 0.0, 0.0, q), "map").unwrap_err();
        assert!(inf.to_string().contains("orientation.w = inf"), "{inf}");
        let zero = msgs::Quaternion {
            x: 0.0,
            y: 0.0,
            z: 0.0,
            w: 0.0,
        };
        let err = initial_pose(&estimate("map", 0.0, 0.0, zero), "map").unwrap_err();
        assert!(matches!(err, BadPose::ZeroQuaternion { .. }), "{err}");
        let far = initial_pose(&estimate("map", 0.0, -1e308, Default::default()), "map");
        assert_eq!(
            far.unwrap_err().to_string(),
            "pose.pose.position.y = -1e308 m is over 10000 m from the map's origin"
        );
    }

    #[test]
    fn the_newest_good_pose_wins_and_every_bad_one_is_reported() {
        let good = |x| estimate("map", x, 0.0, Default::default());
        let messages = [
            good(1.0),
            good(2.0),
            estimate("odom", 3.0, 0.0, Default::default()),
            good(f64::NAN),
        ];
        let (pose, refused) = newest(&messages, "map", initial_pose);
        assert_eq!(pose.map(|p| p.x), Some(2.0));
        assert_eq!(refused.len(), 2);
        assert_eq!(newest(&[], "map", initial_pose), (None, vec![]));
    }

    #[test]
    fn a_goal_pose_is_read_and_refused_as_an_estimate_is_with_its_own_field_names() {
        let mut goal = msgs::PoseStamped {
            header: msgs::Header::new(msgs::Time::default(), "map"),
            ..Default::default()
        };
        goal.pose.position.x = 1.25;
        goal.pose.orientation = msgs::Quaternion::from_yaw(-1.0);
        let p = goal_pose(&goal, "map").unwrap();
        assert!((p.x - 1.25).abs() < 1e-12 && (p.theta + 1.0).abs() < 1e-12);
        goal.pose.position.y = f64::NAN;
        let err = goal_pose(&goal, "map").unwrap_err().to_string();
        assert_eq!(err, "pose.position.y = NaN is not finite");
    }
}
