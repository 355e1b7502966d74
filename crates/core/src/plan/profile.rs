//! The velocity profile (seed 004 section B): a curvature speed limit, a forward pass for
//! acceleration, a backward pass for deceleration, then trapezoidal time stamps.

use super::smooth::PathSample;
use super::trajectory::{Trajectory, TrajectoryPoint};

/// Seed 004 section B: the epsilon in v_limit = sqrt(a_lat / (kappa + eps)), 1/m.
const CURVATURE_EPSILON: f64 = 1e-6;

/// Speed and acceleration limits of a profile.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProfileLimits {
    /// Top speed, m/s (seed 004: 0.22).
    pub max_speed: f64,
    /// Acceleration and deceleration limit, m/s^2 (seed 004: 0.6).
    pub max_accel: f64,
    /// Lateral (centripetal) acceleration limit, m/s^2 (seed 004: 0.9).
    pub max_lateral_accel: f64,
    /// Speed at the first sample, m/s (capped by the limits there).
    pub start_speed: f64,
    /// Speed at the last sample, m/s.
    pub end_speed: f64,
}

impl Default for ProfileLimits {
    fn default() -> Self {
        Self {
            max_speed: 0.22,
            max_accel: 0.6,
            max_lateral_accel: 0.9,
            start_speed: 0.0,
            end_speed: 0.0,
        }
    }
}

/// Times a sampled path. One sample gives one point at t = 0.
///
/// Time stamps use seed 004's trapezoid, dt = Δs / ((v[i] + v[i-1]) / 2). Under the constant
/// acceleration between two samples that is the exact kinematic time, and it stays finite at
/// the ends where v = 0: after both passes a sample next to a stopped one has
/// v = sqrt(2 a Δs) > 0, so the mean speed of a segment is zero only when its length is
/// (repeated samples), and then dt = 0.
pub fn profile(samples: &[PathSample], limits: &ProfileLimits) -> Trajectory {
    let n = samples.len();
    if n == 0 {
        return Trajectory::default();
    }
    // Seed 004 section B: s[i] = s[i-1] + hypot(Δx, Δy).
    let mut s = vec![0.0; n];
    for i in 1..n {
        let (a, b) = (samples[i - 1].position, samples[i].position);
        s[i] = s[i - 1] + (b.x - a.x).hypot(b.y - a.y);
    }
    // Seed 004 section B: v_limit = min(v_max, sqrt(a_lat / (kappa + eps))).
    let mut v: Vec<f64> = samples
        .iter()
        .map(|p| {
            let lateral =
                (limits.max_lateral_accel / (p.curvature.abs() + CURVATURE_EPSILON)).sqrt();
            limits.max_speed.min(lateral)
        })
        .collect();
    v[0] = v[0].min(limits.start_speed.max(0.0));
    if n > 1 {
        v[n - 1] = v[n - 1].min(limits.end_speed.max(0.0));
    }
    let a2 = 2.0 * limits.max_accel;
    // Seed 004 section B forward pass: v[i] = min(v_limit[i], sqrt(v[i-1]^2 + 2 a_max Δs)).
    for i in 1..n {
        v[i] = v[i].min((v[i - 1] * v[i - 1] + a2 * (s[i] - s[i - 1])).sqrt());
    }
    // Seed 004 section B backward pass: v[i] = min(v[i], sqrt(v[i+1]^2 + 2 a_max Δs)).
    for i in (0..n.saturating_sub(1)).rev() {
        v[i] = v[i].min((v[i + 1] * v[i + 1] + a2 * (s[i + 1] - s[i])).sqrt());
    }
    let mut t = 0.0;
    let points = (0..n)
        .map(|i| {
            if i > 0 {
                let ds = s[i] - s[i - 1];
                let mean = 0.5 * (v[i] + v[i - 1]);
                // Seed 004 section B: dt = Δs / ((v[i] + v[i-1]) / 2), t[i] = t[i-1] + dt.
                if ds > 0.0 && mean > 0.0 {
                    t += ds / mean;
                }
            }
            TrajectoryPoint {
                position: samples[i].position,
                heading: samples[i].heading,
                curvature: samples[i].curvature,
                s: s[i],
                v: v[i],
                t,
            }
        })
        .collect();
    Trajectory::new(points)
}
