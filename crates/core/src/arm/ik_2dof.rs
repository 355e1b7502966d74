//! Seed 002's constrained inverse kinematics: two degrees of freedom, shoulder and elbow.
//!
//! What is constrained, exactly: the tool's pitch is always `fixed_pitch` (the wrist,
//! joint 4, is slaved to it: theta4 = fixed_pitch - (theta2 + theta3 + offsets)), so a
//! target may not ask for another pitch (`PitchLocked`). Joint 1 is not solved either: it
//! is the yaw that brings the target into the arm's plane (atan2(y, x), or the opposite
//! yaw with the arm reaching back, whichever its limits allow). That leaves the shoulder
//! and the elbow to put the wrist, L4 behind the tool along the fixed pitch, at the
//! target's reach and height: a planar two-link problem, started from the law of cosines
//! and then stepped by Newton on the 2 x 2 planar Jacobian, as seed 002 iterates its IK
//! (its cap: "around 100" iterations).

use super::config::ArmConfig;
use super::kinematics::link_pitches;
use super::planar;
use super::refine::miss;
use super::{Joints, Solution, Target, Unreachable};
use crate::geometry::wrap_angle;

/// Newton steps at most (seed 002: "the number of iterations was kept at around 100").
const MAX_ITERATIONS: u32 = 100;

pub(super) fn solve(
    cfg: &ArmConfig,
    t: &Target,
    current: &Joints,
) -> Result<Solution, Unreachable> {
    let locked = cfg.fixed_pitch;
    if let Some(asked) = t.pitch
        && wrap_angle(asked - locked).abs() > 1e-9
    {
        return Err(Unreachable::PitchLocked { asked, locked });
    }
    planar::out_of_span(cfg, t.x, t.y, t.z)?;
    let planes = planar::planes(cfg, t.x, t.y, t.z, current);
    let ways = planar::all_ways(cfg, &planes, locked);
    let chosen = match planar::choose(cfg, &ways, current) {
        None => return Err(planar::refusal(cfg, &ways, locked)),
        Some(Err(manipulability)) => return Err(Unreachable::Singular { manipulability }),
        Some(Ok(chosen)) => chosen,
    };
    let target = Target {
        pitch: Some(locked),
        ..*t
    };
    Ok(chosen.refined(cfg, newton(cfg, chosen.joints, &target)))
}

/// Newton on (reach, height) over (theta2, theta3) with theta4 slaved to the pitch.
fn newton(cfg: &ArmConfig, mut q: Joints, target: &Target) -> (Joints, u32, f64) {
    let [l2, l3, _] = cfg.links;
    let pitch = cfg.fixed_pitch;
    let (sy, cy) = (q.0[0] + cfg.joint_offsets[0]).sin_cos();
    let mut steps = 0;
    loop {
        let (e, _) = miss(cfg, &q, target);
        let residual = e.norm();
        if residual < cfg.refine.tolerance || steps >= MAX_ITERATIONS {
            return (q, steps, residual);
        }
        // The miss in the arm's plane: along the yaw, and up.
        let (er, ez) = (e.x * cy + e.y * sy, e.z);
        let [p2, p3, _] = link_pitches(cfg, &q.0);
        let (s2, c2) = p2.sin_cos();
        let (s3, c3) = p3.sin_cos();
        // d(r, z)/d(theta2, theta3) with the tool's pitch held: the wrist point moves, the
        // tool is carried along unturned.
        let (a, b) = (-(l2 * s2 + l3 * s3), -l3 * s3);
        let (c, d) = (-(l2 * c2 + l3 * c3), -l3 * c3);
        let det = a * d - b * c;
        if det.abs() < 1e-12 {
            return (q, steps, residual);
        }
        let d2 = (d * er - b * ez) / det;
        let d3 = (a * ez - c * er) / det;
        q.0[1] = (q.0[1] + d2).clamp(cfg.limits.min[1], cfg.limits.max[1]);
        q.0[2] = (q.0[2] + d3).clamp(cfg.limits.min[2], cfg.limits.max[2]);
        let [_, p3, _] = link_pitches(cfg, &q.0);
        q.0[3] = (pitch - p3 - cfg.joint_offsets[3]).clamp(cfg.limits.min[3], cfg.limits.max[3]);
        steps += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arm::config::Solver;
    use crate::arm::forward;
    use std::f64::consts::FRAC_PI_2;

    fn two_dof() -> ArmConfig {
        ArmConfig {
            solver: Solver::TwoDof,
            ..ArmConfig::default()
        }
    }

    #[test]
    fn right_angle_elbow_by_hand() {
        let c = two_dof();
        let lean = 0.024f64.atan2(0.128);
        let s = solve(&c, &Target::point(0.124, 0.0, 0.057), &Joints::default()).unwrap();
        let want = [0.0, -lean, lean, FRAC_PI_2];
        for (i, w) in want.iter().enumerate() {
            assert!((s.joints.0[i] - w).abs() < 1e-12, "{s:?}");
        }
    }

    #[test]
    fn the_pitch_is_kept_and_another_refused() {
        let c = two_dof();
        let s = solve(&c, &Target::point(0.15, 0.1, 0.0), &Joints::default()).unwrap();
        let p = forward(&c, &s.joints);
        assert!(
            (p.pitch - FRAC_PI_2).abs() < 1e-9 && s.residual < 1e-6,
            "{p:?}"
        );
        let t = Target {
            pitch: Some(0.0),
            ..Target::point(0.2, 0.0, 0.1)
        };
        assert!(matches!(
            solve(&c, &t, &Joints::default()),
            Err(Unreachable::PitchLocked { .. })
        ));
    }

    #[test]
    fn newton_pulls_a_nearby_start_onto_the_target() {
        let c = two_dof();
        let truth = Joints([0.3, -0.2, 0.3, FRAC_PI_2 - 0.1]);
        let target = Target::from(forward(&c, &truth));
        let start = Joints([0.3, -0.17, 0.25, FRAC_PI_2 - 0.08]);
        let (q, steps, residual) = newton(&c, start, &target);
        assert!(residual < 1e-6 && steps > 0, "{residual} {steps}");
        assert!((q.0[1] - truth.0[1]).abs() < 1e-6, "{q:?}");
    }
}
