//! Differential-drive kinematics: wheel travel and the
//! exact pose update for one physics step.

use crate::geometry::Pose2;
use std::f64::consts::PI;

pub use crate::slam::odometry::wheel_travel;

/// Pose after the wheels travel `l` and `r` metres, integrated exactly along the arc.
///
/// Seed 001 section 3 turns by alpha = (r - l) / WIDTH on a circle; this uses the circle
/// of the robot centre, radius (l + r) / (2 alpha), written in chord form: the centre moves
/// d * sinc(alpha / 2) along heading theta + alpha / 2 with d = (l + r) / 2 (Thrun, Burgard
/// & Fox, Probabilistic Robotics, eq. 5.9, rearranged), which stays accurate as alpha -> 0.
pub fn integrate(pose: Pose2, l: f64, r: f64, track: f64) -> Pose2 {
    let alpha = (r - l) / track;
    let d = (l + r) / 2.0;
    let half = alpha / 2.0;
    let chord = if half.abs() < 1e-9 {
        d
    } else {
        d * half.sin() / half
    };
    let (s, c) = (pose.theta + half).sin_cos();
    let mut theta = pose.theta + alpha;
    if theta > PI || theta <= -PI {
        theta = crate::geometry::wrap_angle(theta);
    }
    Pose2::new(pose.x + chord * c, pose.y + chord * s, theta)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::robot::RobotConfig;
    use crate::geometry::Twist;

    #[test]
    fn straight_travel_moves_along_heading() {
        let p = integrate(Pose2::new(1.0, 1.0, PI / 2.0), 0.3, 0.3, 0.11);
        assert!(
            (p.x - 1.0).abs() < 1e-12
                && (p.y - 1.3).abs() < 1e-12
                && (p.theta - PI / 2.0).abs() < 1e-12
        );
    }

    #[test]
    fn spin_in_place_keeps_position_and_turns_by_alpha() {
        // Wheels travel -/+ pi * track / 4: a quarter turn on the spot.
        let b = 0.11;
        let q = PI * b / 4.0;
        let p = integrate(Pose2::new(0.5, -0.5, 0.0), -q, q, b);
        assert!((p.x - 0.5).abs() < 1e-12 && (p.y + 0.5).abs() < 1e-12);
        assert!((p.theta - PI / 2.0).abs() < 1e-12);
    }

    #[test]
    fn quarter_circle_lands_on_the_hand_worked_point() {
        // Centre radius R = 1 m, quarter turn left from the origin facing +x ends at (1, 1).
        let b = 0.11;
        let (l, r) = ((1.0 - b / 2.0) * PI / 2.0, (1.0 + b / 2.0) * PI / 2.0);
        let p = integrate(Pose2::default(), l, r, b);
        assert!(
            (p.x - 1.0).abs() < 1e-12 && (p.y - 1.0).abs() < 1e-12,
            "{p:?}"
        );
        assert!((p.theta - PI / 2.0).abs() < 1e-12);
    }

    #[test]
    fn limits_clip_speed_and_ramp_acceleration() {
        let robot = RobotConfig::default();
        let c = robot.clamp_twist(Twist::new(5.0, f64::NAN));
        assert_eq!(c, Twist::new(robot.max_linear, 0.0));
        let v = robot.ramp(Twist::ZERO, c, 0.01);
        assert!((v.linear - robot.max_linear_accel * 0.01).abs() < 1e-15);
        let (l, r) = wheel_travel(Twist::new(0.0, 2.0), 0.1, 0.5);
        assert!((l + 0.05).abs() < 1e-15 && (r - 0.05).abs() < 1e-15);
    }
}
