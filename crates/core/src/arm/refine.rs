//! Seed 000 section 4.3.2's refinement: damped-least-squares Newton steps from the closed
//! form until the tool is within the tolerance of the target or the steps run out.

use super::config::ArmConfig;
use super::kinematics::{forward, jacobian};
use super::{Joints, Target};
use crate::geometry::wrap_angle;
use nalgebra::{Matrix3, Matrix3x4, Matrix4, Vector3, Vector4};

/// Largest step, rad (seed 000: step_size = min(1, 0.1 / |delta theta|)).
const MAX_STEP: f64 = 0.1;

/// The tool's distance from the target at `q`, metres, and the pitch error (0 when the
/// target leaves the pitch free).
pub(super) fn miss(cfg: &ArmConfig, q: &Joints, target: &Target) -> (Vector3<f64>, f64) {
    let p = forward(cfg, q);
    let e = Vector3::new(target.x - p.x, target.y - p.y, target.z - p.z);
    let pitch = target.pitch.map_or(0.0, |t| wrap_angle(t - p.pitch));
    (e, pitch)
}

/// Refines `q` toward `target`: (joints, steps taken, the tool's final distance, m).
pub(super) fn refine(cfg: &ArmConfig, mut q: Joints, target: &Target) -> (Joints, u32, f64) {
    let tolerance = cfg.refine.tolerance;
    let lambda2 = cfg.refine.damping * cfg.refine.damping;
    let mut steps = 0;
    loop {
        let (e, pitch_error) = miss(cfg, &q, target);
        let residual = e.norm();
        if (residual < tolerance && pitch_error.abs() < tolerance)
            || steps >= cfg.refine.max_iterations
        {
            return (q, steps, residual);
        }
        let j = jacobian(cfg, &q);
        // delta = J^T (J J^T + lambda^2 I)^-1 e (seed 000 section 4.3.2), with the pitch
        // row when a pitch is asked, else the position rows alone.
        let delta: Vector4<f64> = if target.pitch.is_some() {
            let e4 = Vector4::new(e.x, e.y, e.z, pitch_error);
            match (j * j.transpose() + Matrix4::identity() * lambda2).try_inverse() {
                Some(inv) => j.transpose() * (inv * e4),
                None => return (q, steps, residual),
            }
        } else {
            let jp: Matrix3x4<f64> = j.fixed_rows::<3>(0).into_owned();
            match (jp * jp.transpose() + Matrix3::identity() * lambda2).try_inverse() {
                Some(inv) => jp.transpose() * (inv * e),
                None => return (q, steps, residual),
            }
        };
        let scale = (MAX_STEP / (delta.norm() + 1e-6)).min(1.0);
        for i in 0..4 {
            // Seed 000's apply_joint_limits after each step.
            q.0[i] = (q.0[i] + scale * delta[i]).clamp(cfg.limits.min[i], cfg.limits.max[i]);
        }
        steps += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_back_onto_a_target_from_nearby_joints() {
        let c = ArmConfig::default();
        let truth = Joints([0.2, -0.3, 0.4, 0.5]);
        let target = Target::from(forward(&c, &truth));
        let start = Joints([0.21, -0.31, 0.38, 0.52]);
        let (q, steps, residual) = refine(&c, start, &target);
        assert!(residual < 1e-6, "{residual} after {steps}");
        assert!(steps > 0 && steps <= c.refine.max_iterations);
        for i in 0..4 {
            assert!((q.0[i] - truth.0[i]).abs() < 1e-4, "{q:?}");
        }
    }

    #[test]
    fn a_target_within_the_tolerance_takes_no_step() {
        let c = ArmConfig::default();
        let q = Joints([0.1, 0.2, 0.3, 0.4]);
        let (_, steps, residual) = refine(&c, q, &Target::from(forward(&c, &q)));
        assert_eq!(steps, 0);
        assert!(residual < 1e-12);
    }
}
