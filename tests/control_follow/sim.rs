//! The test bench: hand-built trajectories and a unicycle that lags its commands.

use navdeck::geometry::{Point2, Pose2, Twist, wrap_angle};
use navdeck::plan::trajectory::{Trajectory, TrajectoryPoint};
use std::f64::consts::FRAC_PI_2;

/// Cruise speed of the hand-built trajectories, m/s.
pub const CRUISE: f64 = 0.2;

/// The simulated base's acceleration limits, m/s^2 and rad/s^2 (1.0: seed 004 section B's
/// "actual" robot; 8: navdeck's).
const LINEAR_ACCEL: f64 = 1.0;
const ANGULAR_ACCEL: f64 = 8.0;

/// A trajectory through dense polyline samples: heading and curvature by central differences,
/// speed CRUISE with 0 at both ends ramped at 0.6 m/s^2, time integrated from the speed.
pub fn trajectory(samples: &[Point2]) -> Trajectory {
    let n = samples.len();
    let mut s = vec![0.0; n];
    for i in 1..n {
        s[i] = s[i - 1] + samples[i].distance(samples[i - 1]);
    }
    let length = s[n - 1];
    let heading: Vec<f64> = (0..n)
        .map(|i| {
            let (a, b) = (samples[i.saturating_sub(1)], samples[(i + 1).min(n - 1)]);
            (b.y - a.y).atan2(b.x - a.x)
        })
        .collect();
    let mut points: Vec<TrajectoryPoint> = (0..n)
        .map(|i| {
            let (a, b) = (i.saturating_sub(1), (i + 1).min(n - 1));
            let curvature = if s[b] > s[a] {
                wrap_angle(heading[b] - heading[a]) / (s[b] - s[a])
            } else {
                0.0
            };
            // v^2 = 2 a d from either end (0.6 m/s^2, seed 004 section C's rate limit).
            let ramp = (2.0 * 0.6 * s[i].min(length - s[i])).sqrt();
            TrajectoryPoint {
                position: samples[i],
                heading: heading[i],
                curvature,
                s: s[i],
                v: CRUISE.min(ramp),
                t: 0.0,
            }
        })
        .collect();
    for i in 1..n {
        let mean = ((points[i].v + points[i - 1].v) / 2.0).max(1e-3);
        points[i].t = points[i - 1].t + (s[i] - s[i - 1]) / mean;
    }
    Trajectory::new(points)
}

/// A straight line along +x, `length` metres, a sample every centimetre.
pub fn line(length: f64) -> Trajectory {
    let n = (length / 0.01).round() as usize;
    trajectory(
        &(0..=n)
            .map(|k| Point2::new(length * k as f64 / n as f64, 0.0))
            .collect::<Vec<_>>(),
    )
}

/// The S-curve: 0.3 m straight, a quarter circle of radius 0.5 m to the left, a quarter
/// circle of radius 0.5 m to the right, 0.3 m straight; 1.97 m, a sample every centimetre.
pub fn s_curve() -> Trajectory {
    let r = 0.5;
    let quarter = FRAC_PI_2 * r;
    let length = 0.6 + 2.0 * quarter;
    let at = |s: f64| -> Point2 {
        if s <= 0.3 {
            return Point2::new(s, 0.0);
        }
        let u = s - 0.3;
        if u <= quarter {
            let a = u / r;
            return Point2::new(0.3 + r * a.sin(), r - r * a.cos());
        }
        // End of the left turn: (0.8, 0.5) heading +y; the right turn's centre is at (1.3, 0.5).
        let u = u - quarter;
        if u <= quarter {
            let a = u / r;
            return Point2::new(1.3 - r * a.cos(), 0.5 + r * a.sin());
        }
        Point2::new(1.3 + (u - quarter), 1.0)
    };
    let n = (length / 0.01).round() as usize;
    trajectory(
        &(0..=n)
            .map(|k| at(length * k as f64 / n as f64))
            .collect::<Vec<_>>(),
    )
}

/// An ideal unicycle whose wheel speeds lag the command: accelerations of at most
/// 1.0 m/s^2 (seed 004 section B) and 8 rad/s^2 (navdeck's), integrated in 10 ms steps.
pub struct Unicycle {
    pub pose: Pose2,
    pub velocity: Twist,
}

impl Unicycle {
    pub fn new(pose: Pose2) -> Self {
        Self {
            pose,
            velocity: Twist::ZERO,
        }
    }

    pub fn drive(&mut self, command: Twist, dt: f64) {
        let h = 0.01;
        for _ in 0..(dt / h).round() as usize {
            let v = &mut self.velocity;
            v.linear += (command.linear - v.linear).clamp(-LINEAR_ACCEL * h, LINEAR_ACCEL * h);
            v.angular += (command.angular - v.angular).clamp(-ANGULAR_ACCEL * h, ANGULAR_ACCEL * h);
            let mid = self.pose.theta + v.angular * h / 2.0;
            self.pose.x += v.linear * h * mid.cos();
            self.pose.y += v.linear * h * mid.sin();
            self.pose.theta = wrap_angle(self.pose.theta + v.angular * h);
        }
    }
}
