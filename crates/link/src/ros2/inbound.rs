//! Checking and converting what the robot publishes: odometry, wheel joints, scans.
//! Non-finite or impossible values are refused here, before the estimator sees them.

use crate::{LaserScan, WheelTravel};
use navdeck_core::data::frame_check::{MAX_BEAMS, check_scan};
use navdeck_core::geometry::{Pose2, wrap_angle};
use navdeck_msgs::ros as msgs;

/// Why an incoming message was dropped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Refusal {
    NonFinite,
    /// Wheels that would have moved faster than the robot can.
    Jump,
    /// A scan whose angles or sizes make no sense.
    BadScan,
    /// Joint names or array lengths that do not match.
    BadJoints,
}

impl Refusal {
    pub fn label(self) -> &'static str {
        match self {
            Self::NonFinite => "non-finite value",
            Self::Jump => "impossible jump",
            Self::BadScan => "malformed scan",
            Self::BadJoints => "wheel joints missing",
        }
    }
}

/// The planar pose in an Odometry message.
pub fn odom_pose(odom: &msgs::Odometry) -> Result<Pose2, Refusal> {
    let p = odom.pose.pose.position;
    let q = odom.pose.pose.orientation;
    if !(p.x.is_finite() && p.y.is_finite() && q.is_finite()) {
        return Err(Refusal::NonFinite);
    }
    Ok(Pose2::new(p.x, p.y, q.yaw()))
}

/// Seconds in a header stamp, or None if it is unset.
pub fn stamp_seconds(header: &msgs::Header) -> Option<f64> {
    let t = header.stamp.seconds();
    (t > 0.0).then_some(t)
}

/// Left and right wheel angles (radians) from a JointState, by joint name.
pub fn wheel_angles(js: &msgs::JointState, left: &str, right: &str) -> Result<(f64, f64), Refusal> {
    let find = |name: &str| {
        js.name
            .iter()
            .position(|n| n == name)
            .and_then(|i| js.position.get(i).copied())
    };
    let (Some(l), Some(r)) = (find(left), find(right)) else {
        return Err(Refusal::BadJoints);
    };
    if !(l.is_finite() && r.is_finite()) {
        return Err(Refusal::NonFinite);
    }
    Ok((l, r))
}

/// Wheel travel between two joint readings: arc = angle x radius (seed 001's l and r).
/// A travel faster than `max_speed` over `dt` (plus a 5 cm allowance) is refused.
pub fn joint_travel(
    before: (f64, f64),
    after: (f64, f64),
    radius: f64,
    dt: f64,
    max_speed: f64,
) -> Result<WheelTravel, Refusal> {
    let travel = WheelTravel {
        left: (after.0 - before.0) * radius,
        right: (after.1 - before.1) * radius,
    };
    check_travel(travel, dt, max_speed)
}

/// The wheel travel that moves a differential-drive robot from `before` to `after`:
/// the inverse of seed 001's motion model, with Δs along the mean heading and
/// Δθ = (r - l) / b, so l = Δs - bΔθ/2 and r = Δs + bΔθ/2.
pub fn odom_travel(
    before: Pose2,
    after: Pose2,
    track: f64,
    dt: f64,
    max_speed: f64,
) -> Result<WheelTravel, Refusal> {
    let dtheta = wrap_angle(after.theta - before.theta);
    let mid = before.theta + 0.5 * dtheta;
    let ds = (after.x - before.x) * mid.cos() + (after.y - before.y) * mid.sin();
    let travel = WheelTravel {
        left: ds - 0.5 * track * dtheta,
        right: ds + 0.5 * track * dtheta,
    };
    check_travel(travel, dt, max_speed)
}

fn check_travel(travel: WheelTravel, dt: f64, max_speed: f64) -> Result<WheelTravel, Refusal> {
    if !(travel.left.is_finite() && travel.right.is_finite()) {
        return Err(Refusal::NonFinite);
    }
    let limit = max_speed * dt.max(0.0) + 0.05;
    if travel.left.abs() > limit || travel.right.abs() > limit {
        return Err(Refusal::Jump);
    }
    Ok(travel)
}

/// A LaserScan as navdeck's scan: ranges outside [range_min, range_max] or non-finite
/// become "no return" (REP 117), the whole scan is refused when its geometry or size
/// breaks the one frame check's bounds (`frame_check::check_scan`).
pub fn scan(msg: &msgs::LaserScan) -> Result<LaserScan, Refusal> {
    let geometry = [
        msg.angle_min,
        msg.angle_increment,
        msg.range_min,
        msg.range_max,
    ];
    if geometry.iter().any(|v| !v.is_finite()) {
        return Err(Refusal::NonFinite);
    }
    // Counted before the ranges are copied: the one frame check's bound.
    if msg.ranges.len() > MAX_BEAMS {
        return Err(Refusal::BadScan);
    }
    let (range_min, range_max) = (msg.range_min, msg.range_max);
    let ranges = msg
        .ranges
        .iter()
        .map(|&r| {
            if r.is_finite() && r >= range_min && r <= range_max {
                r
            } else {
                f32::INFINITY
            }
        })
        .collect();
    let mut scan = LaserScan {
        angle_min: f64::from(msg.angle_min),
        angle_increment: f64::from(msg.angle_increment),
        range_min: f64::from(range_min),
        range_max: f64::from(range_max),
        ranges,
    };
    match check_scan(&mut scan) {
        Ok(_) => Ok(scan),
        Err(_) => Err(Refusal::BadScan),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn odom_at(x: f64, y: f64, yaw: f64) -> msgs::Odometry {
        let mut o = msgs::Odometry::default();
        o.pose.pose.position.x = x;
        o.pose.pose.position.y = y;
        o.pose.pose.orientation = msgs::Quaternion::from_yaw(yaw);
        o
    }

    #[test]
    fn odometry_pose_and_its_wheel_travel_round_trip_through_the_motion_model() {
        let a = odom_pose(&odom_at(1.0, 2.0, 0.3)).unwrap();
        assert!((a.theta - 0.3).abs() < 1e-12);
        let b = Pose2::new(1.0 + 0.05 * 0.35f64.cos(), 2.0 + 0.05 * 0.35f64.sin(), 0.4);
        let w = odom_travel(a, b, 0.16, 0.1, 1.0).unwrap();
        // Forward: Δs = (l + r)/2, Δθ = (r - l)/b.
        assert!(((w.left + w.right) / 2.0 - 0.05).abs() < 1e-9);
        assert!(((w.right - w.left) / 0.16 - 0.1).abs() < 1e-9);
    }

    #[test]
    fn non_finite_and_impossible_values_are_refused() {
        assert_eq!(
            odom_pose(&odom_at(f64::NAN, 0.0, 0.0)),
            Err(Refusal::NonFinite)
        );
        let a = Pose2::new(0.0, 0.0, 0.0);
        let far = Pose2::new(5.0, 0.0, 0.0);
        assert_eq!(odom_travel(a, far, 0.16, 0.1, 1.0), Err(Refusal::Jump));
        assert_eq!(
            joint_travel((0.0, 0.0), (1e6, 0.0), 0.033, 0.1, 1.0),
            Err(Refusal::Jump)
        );
        let ok = joint_travel((0.0, 0.0), (1.0, 2.0), 0.033, 0.1, 1.0).unwrap();
        assert!((ok.left - 0.033).abs() < 1e-12 && (ok.right - 0.066).abs() < 1e-12);
    }

    #[test]
    fn wheel_joints_are_found_by_name_in_any_order() {
        let js = msgs::JointState {
            name: vec!["wheel_right_joint".into(), "wheel_left_joint".into()],
            position: vec![2.0, 1.0],
            ..Default::default()
        };
        assert_eq!(
            wheel_angles(&js, "wheel_left_joint", "wheel_right_joint"),
            Ok((1.0, 2.0))
        );
        assert_eq!(
            wheel_angles(&js, "left", "wheel_right_joint"),
            Err(Refusal::BadJoints)
        );
    }

    #[test]
    fn scans_keep_good_ranges_and_mark_the_rest_as_no_return() {
        let msg = msgs::LaserScan {
            angle_min: 0.0,
            angle_increment: 0.5,
            range_min: 0.12,
            range_max: 3.5,
            ranges: vec![1.0, f32::NAN, 0.0, 9.0, 3.5],
            ..Default::default()
        };
        let s = scan(&msg).unwrap();
        assert_eq!(s.ranges[0], 1.0);
        assert!(s.ranges[1..4].iter().all(|r| r.is_infinite()));
        assert_eq!(s.ranges[4], 3.5);
        let bad = msgs::LaserScan {
            angle_increment: f32::NAN,
            ..msg.clone()
        };
        assert_eq!(scan(&bad), Err(Refusal::NonFinite));
        let empty = msgs::LaserScan {
            ranges: vec![],
            ..msg
        };
        assert_eq!(scan(&empty), Err(Refusal::BadScan));
    }
}
