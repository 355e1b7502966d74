//! Dead reckoning from wheel travel with seed 001's motion model (section 3, "Prediction Step").

use crate::data::WheelTravel;
use crate::geometry::{Pose2, Twist, wrap_angle};

/// Below this difference between the wheels (metres) the motion counts as straight.
pub const STRAIGHT_THRESHOLD: f64 = 1e-9;

/// Seed 001 section 3: pose after the wheels travel `l` and `r` on a base of width `track`.
/// Arc when |r - l| exceeds the threshold, straight line otherwise.
pub fn predict_pose(pose: Pose2, wheels: WheelTravel, track: f64) -> Pose2 {
    let (l, r) = (wheels.left, wheels.right);
    if (r - l).abs() > STRAIGHT_THRESHOLD {
        // alpha = (r - l) / WIDTH; R = l / alpha is the left wheel's radius, so the centre
        // runs on R + WIDTH/2 (the seed's R is measured to the left wheel).
        let alpha = (r - l) / track;
        let radius = l / alpha + track / 2.0;
        let (theta, next) = (pose.theta, pose.theta + alpha);
        Pose2::new(
            pose.x - radius * theta.sin() + radius * next.sin(),
            pose.y + radius * theta.cos() - radius * next.cos(),
            wrap_angle(next),
        )
    } else {
        // Seed 001 straight motion: x + l cos(theta), y + l sin(theta).
        Pose2::new(
            pose.x + l * pose.theta.cos(),
            pose.y + l * pose.theta.sin(),
            pose.theta,
        )
    }
}

/// Left and right wheel travel in metres for holding `twist` for `h` seconds: each wheel
/// runs at v -/+ omega * track / 2 (inverse of seed 001 section 3's alpha = (r - l) / WIDTH).
pub fn wheel_travel(twist: Twist, track: f64, h: f64) -> (f64, f64) {
    let half = twist.angular * track / 2.0;
    ((twist.linear - half) * h, (twist.linear + half) * h)
}

/// The twist that produced `wheels` over `elapsed` seconds: v = (l + r) / 2dt, w = (r - l) / (track dt).
pub fn twist_from_wheels(wheels: WheelTravel, track: f64, elapsed: f64) -> Twist {
    if elapsed <= 0.0 {
        return Twist::ZERO;
    }
    Twist::new(
        (wheels.left + wheels.right) / (2.0 * elapsed),
        (wheels.right - wheels.left) / (track * elapsed),
    )
}

/// A pose integrated from wheel travel alone; drifts, which is what SLAM will correct.
#[derive(Clone, Debug)]
pub struct Odometry {
    pose: Pose2,
    track: f64,
    distance: f64,
}

impl Odometry {
    pub fn new(start: Pose2, track: f64) -> Self {
        Self {
            pose: start,
            track,
            distance: 0.0,
        }
    }

    pub fn update(&mut self, wheels: WheelTravel) {
        self.pose = predict_pose(self.pose, wheels, self.track);
        self.distance += ((wheels.left + wheels.right) / 2.0).abs();
    }

    pub fn pose(&self) -> Pose2 {
        self.pose
    }

    /// Distance the centre travelled according to the wheels, metres.
    pub fn distance(&self) -> f64 {
        self.distance
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    const TRACK: f64 = 0.11;

    #[test]
    fn straight_travel_moves_along_heading() {
        let p = predict_pose(
            Pose2::new(1.0, 2.0, PI / 2.0),
            WheelTravel {
                left: 0.3,
                right: 0.3,
            },
            TRACK,
        );
        assert!((p.x - 1.0).abs() < 1e-12 && (p.y - 2.3).abs() < 1e-12);
        assert_eq!(p.theta, PI / 2.0);
    }

    #[test]
    fn spin_in_place_turns_without_moving() {
        // Wheels in opposite directions by pi*track/4 each: a quarter turn about the centre.
        let s = PI * TRACK / 4.0;
        let p = predict_pose(Pose2::default(), WheelTravel { left: -s, right: s }, TRACK);
        assert!(p.x.abs() < 1e-12 && p.y.abs() < 1e-12, "{p:?}");
        assert!((p.theta - PI / 2.0).abs() < 1e-12);
    }

    #[test]
    fn quarter_circle_lands_on_the_arc() {
        // Centre radius 1 m, turning left by 90 degrees: from (0,0,0) to (1,1,90 deg).
        let alpha = PI / 2.0;
        let l = (1.0 - TRACK / 2.0) * alpha;
        let r = (1.0 + TRACK / 2.0) * alpha;
        let p = predict_pose(Pose2::default(), WheelTravel { left: l, right: r }, TRACK);
        assert!(
            (p.x - 1.0).abs() < 1e-9 && (p.y - 1.0).abs() < 1e-9,
            "{p:?}"
        );
        assert!((p.theta - alpha).abs() < 1e-12);
    }

    #[test]
    fn twist_recovers_wheel_speeds() {
        let t = twist_from_wheels(
            WheelTravel {
                left: 0.01,
                right: 0.03,
            },
            TRACK,
            0.1,
        );
        assert!((t.linear - 0.2).abs() < 1e-12);
        assert!((t.angular - 0.02 / (TRACK * 0.1)).abs() < 1e-12);
    }
}
