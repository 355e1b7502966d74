//! Forward kinematics, the Jacobian and manipulability (seed 000 sections 4.1.1-4.1.2),
//! and `inverse`, which runs the configured solver.

use super::config::{ArmConfig, Solver};
use super::{Joints, Solution, Target, ToolPose, Unreachable, ik_2dof, ik_4dof};
use crate::geometry::wrap_angle;
use nalgebra::{Matrix3x4, Matrix4};

/// Pitch of links 2, 3 and 4 (upper arm, forearm, tool), REP-103: each is the sum of the
/// joints before it plus their offsets (seed 000 DH theta_i + theta_i,offset).
pub(super) fn link_pitches(cfg: &ArmConfig, q: &[f64; 4]) -> [f64; 3] {
    let o = cfg.joint_offsets;
    let p2 = q[1] + o[1];
    let p3 = p2 + q[2] + o[2];
    [p2, p3, p3 + q[3] + o[3]]
}

/// The tool's pose at joints `q`, in the arm's base frame.
pub fn forward(cfg: &ArmConfig, q: &Joints) -> ToolPose {
    let [l2, l3, l4] = cfg.links;
    let [p2, p3, p4] = link_pitches(cfg, &q.0);
    let (s2, c2) = p2.sin_cos();
    let (s3, c3) = p3.sin_cos();
    let (s4, c4) = p4.sin_cos();
    // Seed 000 DH chain in the arm's plane: reach r along the yaw, height z; a link of
    // pitch p advances L cos p and climbs -L sin p.
    let r = l2 * c2 + l3 * c3 + l4 * c4;
    let z = cfg.base_height - (l2 * s2 + l3 * s3 + l4 * s4);
    let (sy, cy) = (q.0[0] + cfg.joint_offsets[0]).sin_cos();
    ToolPose {
        x: r * cy,
        y: r * sy,
        z,
        pitch: wrap_angle(p4),
    }
}

/// The arm drawn from the side, in its own plane: (reach, height) of the base, the
/// shoulder, the elbow, the wrist and the tool at joints `q` (the same chain as `forward`).
pub fn side_chain(cfg: &ArmConfig, q: &Joints) -> [(f64, f64); 5] {
    let [l2, l3, l4] = cfg.links;
    let pitches = link_pitches(cfg, &q.0);
    let mut points = [
        (0.0, 0.0),
        (0.0, cfg.base_height),
        (0.0, 0.0),
        (0.0, 0.0),
        (0.0, 0.0),
    ];
    for (k, (len, p)) in [l2, l3, l4].into_iter().zip(pitches).enumerate() {
        let (r, z) = points[k + 1];
        points[k + 2] = (r + len * p.cos(), z - len * p.sin());
    }
    points
}

/// d(x, y, z, pitch)/d(theta1..theta4) at `q`: rows x, y, z (m/rad) and pitch (rad/rad).
pub fn jacobian(cfg: &ArmConfig, q: &Joints) -> Matrix4<f64> {
    let [l2, l3, l4] = cfg.links;
    let [p2, p3, p4] = link_pitches(cfg, &q.0);
    let (s2, c2) = p2.sin_cos();
    let (s3, c3) = p3.sin_cos();
    let (s4, c4) = p4.sin_cos();
    let (sy, cy) = (q.0[0] + cfg.joint_offsets[0]).sin_cos();
    let r = l2 * c2 + l3 * c3 + l4 * c4;
    // Turning joint k (2..4) turns every link from k on: dr = -sum L sin p, dz = -sum L cos p.
    let dr = [
        -(l2 * s2 + l3 * s3 + l4 * s4),
        -(l3 * s3 + l4 * s4),
        -(l4 * s4),
    ];
    let dz = [
        -(l2 * c2 + l3 * c3 + l4 * c4),
        -(l3 * c3 + l4 * c4),
        -(l4 * c4),
    ];
    #[rustfmt::skip]
    let j = Matrix4::new(
        -r * sy, cy * dr[0], cy * dr[1], cy * dr[2],
        r * cy,  sy * dr[0], sy * dr[1], sy * dr[2],
        0.0,     dz[0],      dz[1],      dz[2],
        0.0,     1.0,        1.0,        1.0,
    );
    j
}

/// sqrt(det(J J^T)) of the Jacobian's position rows at `q`, m^3 (seed 000 section 4.1.2
/// `analyze_singularity`): 0 where the tool cannot move in some direction (on joint 1's
/// axis, or with the whole arm in line).
pub fn manipulability(cfg: &ArmConfig, q: &Joints) -> f64 {
    let j: Matrix3x4<f64> = jacobian(cfg, q).fixed_rows::<3>(0).into_owned();
    (j * j.transpose()).determinant().max(0.0).sqrt()
}

/// Manipulability under this share of the links' product (their lengths multiplied, m^3)
/// is "near a singularity": a scale-free bar, the same for a small arm and a large one.
pub const NEAR_SINGULAR: f64 = 0.02;

/// Whether `manipulability` (m^3) is near a singularity for this arm: the tool then
/// cannot move in some direction, and a small change of target may swing a joint far.
pub fn near_singular(cfg: &ArmConfig, manipulability: f64) -> bool {
    let scale: f64 = cfg.links.iter().product();
    manipulability < NEAR_SINGULAR * scale
}

/// Joint angles within the config's limits, or the first that is not.
pub fn check_limits(cfg: &ArmConfig, q: &Joints) -> Result<(), Unreachable> {
    for i in 0..4 {
        let (min, max, value) = (cfg.limits.min[i], cfg.limits.max[i], q.0[i]);
        if !(min..=max).contains(&value) {
            return Err(Unreachable::JointLimit {
                joint: i + 1,
                value,
                min,
                max,
            });
        }
    }
    Ok(())
}

/// Seconds to move from `from` to `to` with every joint at most at its speed limit and
/// all arriving together: the slowest joint's travel over its speed.
pub fn move_time(cfg: &ArmConfig, from: &Joints, to: &Joints) -> f64 {
    (0..4)
        .map(|i| (to.0[i] - from.0[i]).abs() / cfg.limits.speed[i])
        .fold(0.0, f64::max)
}

/// Joints that put the tool on `target`, the in-limit solution nearest `current`: seed
/// 000's closed form and refinement (`solver = "4dof"`) or seed 002's constrained
/// solver (`"2dof"`). `cfg` must have passed `validate()`.
pub fn inverse(
    cfg: &ArmConfig,
    target: &Target,
    current: &Joints,
) -> Result<Solution, Unreachable> {
    let fields = [("x", target.x), ("y", target.y), ("z", target.z)];
    let currents = [
        ("current[0]", current.0[0]),
        ("current[1]", current.0[1]),
        ("current[2]", current.0[2]),
        ("current[3]", current.0[3]),
    ];
    let pitch = target.pitch.map(|p| ("pitch", p));
    if let Some((field, _)) = fields
        .into_iter()
        .chain(pitch)
        .chain(currents)
        .find(|(_, v)| !v.is_finite())
    {
        return Err(Unreachable::NotANumber { field });
    }
    match cfg.solver {
        Solver::FourDof => ik_4dof::solve(cfg, target, current),
        Solver::TwoDof => ik_2dof::solve(cfg, target, current),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn zero_pose_by_hand() {
        // Upper arm leans atan2(0.024, 0.128) forward of vertical: it advances
        // 0.130 x 0.024/hypot(0.128, 0.024) = 0.023958 m and climbs 0.130 x 0.128/0.130231
        // = 0.127773 m; forearm and tool level: x = 0.023958 + 0.124 + 0.150.
        let p = forward(&ArmConfig::default(), &Joints([0.0; 4]));
        assert!(close(p.x, 0.297958, 1e-6), "{p:?}");
        assert!(close(p.y, 0.0, 1e-12), "{p:?}");
        assert!(close(p.z, 0.077 + 0.127773, 1e-6), "{p:?}");
        assert!(close(p.pitch, 0.0, 1e-12), "{p:?}");
    }

    #[test]
    fn right_angle_elbow_by_hand() {
        // Upper arm vertical (joint 2 = -atan2(0.024, 0.128)), forearm level (a 90 degree
        // elbow), tool straight down: x = 0.124, z = 0.077 + 0.130 - 0.150 = 0.057.
        let lean = 0.024f64.atan2(0.128);
        let c = ArmConfig::default();
        let p = forward(&c, &Joints([0.0, -lean, lean, FRAC_PI_2]));
        assert!(close(p.x, 0.124, 1e-12) && close(p.y, 0.0, 1e-12), "{p:?}");
        assert!(
            close(p.z, 0.057, 1e-12) && close(p.pitch, FRAC_PI_2, 1e-12),
            "{p:?}"
        );
        // Joint 1 at 90 degrees swings it to the left.
        let p = forward(&c, &Joints([FRAC_PI_2, -lean, lean, FRAC_PI_2]));
        assert!(close(p.x, 0.0, 1e-12) && close(p.y, 0.124, 1e-12), "{p:?}");
    }

    #[test]
    fn jacobian_matches_finite_differences() {
        let c = ArmConfig::default();
        let q = Joints([0.3, -0.4, 0.5, 0.6]);
        let j = jacobian(&c, &q);
        let h = 1e-7;
        for k in 0..4 {
            let mut a = q;
            let mut b = q;
            a.0[k] -= h;
            b.0[k] += h;
            let (pa, pb) = (forward(&c, &a), forward(&c, &b));
            let d = [
                (pb.x - pa.x) / (2.0 * h),
                (pb.y - pa.y) / (2.0 * h),
                (pb.z - pa.z) / (2.0 * h),
                (pb.pitch - pa.pitch) / (2.0 * h),
            ];
            for (row, v) in d.iter().enumerate() {
                assert!(close(j[(row, k)], *v, 1e-6), "J[{row},{k}]");
            }
        }
    }

    #[test]
    fn manipulability_vanishes_on_the_yaw_axis_only() {
        let c = ArmConfig::default();
        let lean = 0.024f64.atan2(0.128);
        // Upper arm and forearm straight up, tool straight down: the tool on joint 1's axis.
        let on_axis = Joints([0.0, -lean, lean - FRAC_PI_2, std::f64::consts::PI]);
        assert!(close(forward(&c, &on_axis).x, 0.0, 1e-12));
        assert!(manipulability(&c, &on_axis) < 1e-12);
        assert!(manipulability(&c, &Joints([0.0; 4])) > 1e-4);
    }

    #[test]
    fn move_time_is_the_slowest_joint() {
        let c = ArmConfig::default();
        let t = move_time(&c, &Joints([0.0; 4]), &Joints([0.48, -0.96, 0.0, 0.1]));
        assert!(close(t, 0.2, 1e-12));
    }

    #[test]
    fn not_a_number_is_named() {
        let c = ArmConfig::default();
        let t = Target::point(0.2, f64::NAN, 0.1);
        assert_eq!(
            inverse(&c, &t, &Joints::default()),
            Err(Unreachable::NotANumber { field: "y" })
        );
        let t = Target {
            pitch: Some(f64::INFINITY),
            ..Target::point(0.2, 0.0, 0.1)
        };
        assert_eq!(
            inverse(&c, &t, &Joints::default()),
            Err(Unreachable::NotANumber { field: "pitch" })
        );
        let t = Target::point(0.2, 0.0, 0.1);
        assert_eq!(
            inverse(&c, &t, &Joints([0.0, 0.0, f64::NAN, 0.0])),
            Err(Unreachable::NotANumber {
                field: "current[2]"
            })
        );
    }
}
