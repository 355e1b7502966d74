//! Jacobians of seed 001's motion model (section 3, "Prediction Step") for the EKF.

use super::odometry::STRAIGHT_THRESHOLD;
use crate::data::WheelTravel;
use crate::geometry::Pose2;
use nalgebra::{Matrix3, Matrix3x2};

/// G = d(pose') / d(pose): seed 001 section 3, with the centre's turning radius.
pub fn state_jacobian(pose: Pose2, wheels: WheelTravel, track: f64) -> Matrix3<f64> {
    let (l, r, th) = (wheels.left, wheels.right, pose.theta);
    let (dx, dy) = if (r - l).abs() > STRAIGHT_THRESHOLD {
        let alpha = (r - l) / track;
        let radius = l / alpha + track / 2.0;
        // Seed 001: -R cos(theta) + R cos(theta + alpha), -R sin(theta) + R sin(theta + alpha).
        (
            radius * ((th + alpha).cos() - th.cos()),
            radius * ((th + alpha).sin() - th.sin()),
        )
    } else {
        // Seed 001 straight case: -l sin(theta), l cos(theta).
        (-l * th.sin(), l * th.cos())
    };
    Matrix3::new(1.0, 0.0, dx, 0.0, 1.0, dy, 0.0, 0.0, 1.0)
}

/// V = d(pose') / d(l, r), which maps the wheels' noise Q into the pose
/// (Thrun, Burgard, Fox, Probabilistic Robotics, 7.4 (Table 7.2), with wheel-travel controls).
pub fn control_jacobian(pose: Pose2, wheels: WheelTravel, track: f64) -> Matrix3x2<f64> {
    let (l, r, th, w) = (wheels.left, wheels.right, pose.theta, track);
    if (r - l).abs() > STRAIGHT_THRESHOLD {
        let alpha = (r - l) / w;
        let radius = l / alpha + w / 2.0;
        let (s0, c0, s1, c1) = (th.sin(), th.cos(), (th + alpha).sin(), (th + alpha).cos());
        // d radius/dl = 1/alpha + l/(w alpha^2), d radius/dr = -l/(w alpha^2); d alpha = (-1, 1)/w.
        let drl = 1.0 / alpha + l / (w * alpha * alpha);
        let drr = -l / (w * alpha * alpha);
        Matrix3x2::new(
            drl * (s1 - s0) - radius * c1 / w,
            drr * (s1 - s0) + radius * c1 / w,
            drl * (c0 - c1) - radius * s1 / w,
            drr * (c0 - c1) + radius * s1 / w,
            -1.0 / w,
            1.0 / w,
        )
    } else {
        // The limit of the arc case as r -> l.
        let (s, c, k) = (th.sin(), th.cos(), l / (2.0 * w));
        Matrix3x2::new(
            0.5 * c + k * s,
            0.5 * c - k * s,
            0.5 * s - k * c,
            0.5 * s + k * c,
            -1.0 / w,
            1.0 / w,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::slam::odometry::predict_pose;

    const TRACK: f64 = 0.11;

    /// Central differences of `predict_pose` against the analytic Jacobians.
    fn check(pose: Pose2, wheels: WheelTravel) {
        let h = 1e-6;
        let f = |p: Pose2, w: WheelTravel| {
            let q = predict_pose(p, w, TRACK);
            [q.x, q.y, q.theta]
        };
        let g = state_jacobian(pose, wheels, TRACK);
        let v = control_jacobian(pose, wheels, TRACK);
        let bump = |i: usize, d: f64| {
            let mut p = pose;
            match i {
                0 => p.x += d,
                1 => p.y += d,
                _ => p.theta += d,
            }
            p
        };
        for j in 0..3 {
            let (a, b) = (f(bump(j, h), wheels), f(bump(j, -h), wheels));
            for i in 0..3 {
                let num = (a[i] - b[i]) / (2.0 * h);
                assert!(
                    (num - g[(i, j)]).abs() < 1e-5,
                    "G[{i},{j}] {num} vs {}",
                    g[(i, j)]
                );
            }
        }
        for j in 0..2 {
            let shift = |d: f64| {
                let mut w = wheels;
                if j == 0 {
                    w.left += d
                } else {
                    w.right += d
                }
                w
            };
            let (a, b) = (f(pose, shift(h)), f(pose, shift(-h)));
            for i in 0..3 {
                let num = (a[i] - b[i]) / (2.0 * h);
                assert!(
                    (num - v[(i, j)]).abs() < 1e-4,
                    "V[{i},{j}] {num} vs {}",
                    v[(i, j)]
                );
            }
        }
    }

    #[test]
    fn jacobians_match_finite_differences_on_an_arc() {
        check(
            Pose2::new(0.3, -0.2, 0.7),
            WheelTravel {
                left: 0.010,
                right: 0.016,
            },
        );
        check(
            Pose2::new(0.0, 0.0, -2.5),
            WheelTravel {
                left: 0.02,
                right: -0.01,
            },
        );
    }

    #[test]
    fn straight_move_jacobian_is_the_seeds() {
        let pose = Pose2::new(1.0, 2.0, 0.5);
        let g = state_jacobian(
            pose,
            WheelTravel {
                left: 0.1,
                right: 0.1,
            },
            TRACK,
        );
        assert!((g[(0, 2)] + 0.1 * 0.5_f64.sin()).abs() < 1e-15);
        assert!((g[(1, 2)] - 0.1 * 0.5_f64.cos()).abs() < 1e-15);
        let v = control_jacobian(
            pose,
            WheelTravel {
                left: 0.1,
                right: 0.1,
            },
            TRACK,
        );
        // Each wheel moves the centre half as far along the heading.
        assert!((v[(0, 0)] + v[(0, 1)] - 0.5_f64.cos()).abs() < 1e-12);
    }
}
