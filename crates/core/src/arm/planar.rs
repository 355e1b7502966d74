//! The closed form at one tool pitch (seed 000 section 4.2.1) and the choice among its
//! solutions (section 4.2.3): both yaws that put the target in the arm's plane (facing
//! it, or facing away and reaching back over the shoulder), both elbow branches.

use super::config::ArmConfig;
use super::kinematics::manipulability;
use super::{Branch, Joints, Solution, Unreachable};
use std::f64::consts::{PI, TAU};

/// A joint may come out this far beyond a limit and be put on it, rad.
pub(super) const LIMIT_SLACK: f64 = 1e-9;
/// The wrist may lie this far outside the shoulder and elbow's reach, m (the law of
/// cosines is clamped there: the tool then misses by about as much).
const REACH_SLACK: f64 = 1e-9;
/// Nearer than this to joint 1's axis the target fixes no yaw: the current one is kept, m.
const ON_AXIS: f64 = 1e-12;

/// One way of reaching the target at one pitch.
#[derive(Clone, Copy, Debug)]
pub(super) struct Way {
    /// Each turned by whole turns to the side of its limits' middle.
    pub joints: [f64; 4],
    pub branch: Branch,
    /// How far inside every constraint: the least of each joint's distance to its nearer
    /// limit (rad) and the wrist's distance inside the shoulder-elbow reach (m); negative
    /// when outside one. A way is possible when this is zero or more.
    pub margin: f64,
    /// The joint (0-based) nearest or farthest beyond a limit.
    pub worst_joint: usize,
    /// The wrist's distance from the shoulder, m, and whether shoulder and elbow span it.
    pub wrist: f64,
    pub wrist_reached: bool,
}

impl Way {
    pub fn possible(&self) -> bool {
        self.margin >= 0.0
    }
}

/// The tool's target in the arm's plane for one yaw: reach `r` (negative: behind the
/// yaw axis) and height `z`, with joint 1 at `yaw` (before its offset is taken off).
#[derive(Clone, Copy, Debug)]
pub(super) struct InPlane {
    pub yaw: f64,
    pub r: f64,
    pub z: f64,
}

/// The two yaws that bring (x, y, z) into the arm's plane: facing it and facing away.
pub(super) fn planes(cfg: &ArmConfig, x: f64, y: f64, z: f64, current: &Joints) -> [InPlane; 2] {
    let rho = x.hypot(y);
    // Seed 000 section 4.2.1 stage 1: theta1 = atan2(y, x); on the axis any yaw will do.
    let yaw = if rho > ON_AXIS {
        y.atan2(x)
    } else {
        current.0[0] + cfg.joint_offsets[0]
    };
    [
        InPlane { yaw, r: rho, z },
        InPlane {
            yaw: yaw + PI,
            r: -rho,
            z,
        },
    ]
}

/// `value` turned by whole turns to lie nearest the middle of min..=max, and how far
/// inside the nearer limit it then is (negative: outside).
fn fit(value: f64, min: f64, max: f64) -> (f64, f64) {
    let mid = 0.5 * (min + max);
    let v = value + ((mid - value) / TAU).round() * TAU;
    (v, (v - min).min(max - v) + LIMIT_SLACK)
}

/// Both elbow branches in one plane with the tool at `pitch`.
pub(super) fn ways(cfg: &ArmConfig, plane: &InPlane, pitch: f64) -> [Way; 2] {
    let [l2, l3, l4] = cfg.links;
    let o = cfg.joint_offsets;
    let (sp, cp) = pitch.sin_cos();
    // Seed 000 section 4.2.1 stage 3, any pitch: the wrist is L4 back along the tool
    // (x_eff = r - L4 cos p, z_eff = z + L4 sin p - d1; the seed's case is p = pi/2).
    let a = plane.r - l4 * cp;
    let b = plane.z + l4 * sp - cfg.base_height;
    let distance = a.hypot(b);
    let reach_margin = (l2 + l3 - distance).min(distance - (l2 - l3).abs()) + REACH_SLACK;
    // The shoulder-to-wrist line's pitch (gamma of seed 000, measured downward).
    let gamma = (-b).atan2(a);
    // Law of cosines (seed 000 section 4.2.1): phi1 at the shoulder, the elbow's interior
    // angle from L2^2 + L3^2 - 2 L2 L3 cos(interior) = R^2.
    let cos_shoulder = if distance > 0.0 {
        ((l2 * l2 + distance * distance - l3 * l3) / (2.0 * l2 * distance)).clamp(-1.0, 1.0)
    } else {
        1.0
    };
    let cos_interior =
        ((l2 * l2 + l3 * l3 - distance * distance) / (2.0 * l2 * l3)).clamp(-1.0, 1.0);
    let shoulder = cos_shoulder.acos();
    let bend = PI - cos_interior.acos();
    [Branch::ElbowUp, Branch::ElbowDown].map(|branch| {
        // Elbow up: the upper arm pitched above the line by phi1, the forearm bent down
        // from it by pi - interior; elbow down mirrors both (seed 000's two solutions).
        let (p2, p3) = match branch {
            Branch::ElbowUp => (gamma - shoulder, gamma - shoulder + bend),
            Branch::ElbowDown => (gamma + shoulder, gamma + shoulder - bend),
        };
        // Undo theta_i + theta_i,offset link by link (seed 000 adds the offset in its IK
        // listing; with its DH table the inverse takes it off).
        let raw = [
            plane.yaw - o[0],
            p2 - o[1],
            p3 - p2 - o[2],
            pitch - p3 - o[3],
        ];
        let mut joints = [0.0; 4];
        let mut joint_margin = f64::INFINITY;
        let mut worst_joint = 0;
        for i in 0..4 {
            let (v, m) = fit(raw[i], cfg.limits.min[i], cfg.limits.max[i]);
            joints[i] = v;
            if m < joint_margin {
                joint_margin = m;
                worst_joint = i;
            }
        }
        Way {
            joints,
            branch,
            margin: joint_margin.min(reach_margin),
            worst_joint,
            wrist: distance,
            wrist_reached: reach_margin >= 0.0,
        }
    })
}

/// All four ways (two yaws, two branches) with the tool at `pitch`.
pub(super) fn all_ways(cfg: &ArmConfig, planes: &[InPlane; 2], pitch: f64) -> [Way; 4] {
    let [a, b] = ways(cfg, &planes[0], pitch);
    let [c, d] = ways(cfg, &planes[1], pitch);
    [a, b, c, d]
}

/// The pitches at which the wrist can be where shoulder and elbow reach within joint
/// 3's limits, in one plane: those with |wrap(pitch + omega)| in an arc per branch.
/// A superset of the possible pitches (joints 2 and 4 are not looked at), computed once
/// so the pitch search can pass over pitches that cannot work.
#[derive(Clone, Copy, Debug)]
pub(super) struct PitchArcs {
    omega: f64,
    arcs: [Option<(f64, f64)>; 2],
}

impl PitchArcs {
    pub fn new(cfg: &ArmConfig, plane: &InPlane) -> Self {
        let [l2, l3, l4] = cfg.links;
        let (h, o3) = (plane.z - cfg.base_height, cfg.joint_offsets[2]);
        let d = plane.r.hypot(h);
        let (lo, hi) = (
            cfg.limits.min[2] + o3 - LIMIT_SLACK,
            cfg.limits.max[2] + o3 + LIMIT_SLACK,
        );
        // The elbow's bend (p3 - p2) within joint 3's limits: 0..pi elbow up, -pi..0 down.
        let bends = |from: f64, to: f64| {
            (-2..=2).fold(None, |hull: Option<(f64, f64)>, k| {
                let shift = k as f64 * TAU;
                let (s, e) = ((lo + shift).max(from), (hi + shift).min(to));
                match hull {
                    _ if s > e => hull,
                    None => Some((s, e)),
                    Some((a, b)) => Some((a.min(s), b.max(e))),
                }
            })
        };
        // Shoulder-to-wrist distance at a bend: R^2 = L2^2 + L3^2 + 2 L2 L3 cos(bend)
        // (the law of cosines with the interior angle pi - |bend|).
        let wrist = |bend: f64| {
            (l2 * l2 + l3 * l3 + 2.0 * l2 * l3 * bend.cos())
                .max(0.0)
                .sqrt()
        };
        let arc = |bend: Option<(f64, f64)>| {
            let (b1, b2) = bend?;
            let (r1, r2) = (wrist(b1), wrist(b2));
            let (near, far) = (r1.min(r2) - REACH_SLACK, r1.max(r2) + REACH_SLACK);
            if d <= ON_AXIS {
                // The wrist is L4 from the shoulder at any pitch.
                return (near..=far).contains(&l4).then_some((0.0, PI));
            }
            // R^2 = d^2 + L4^2 - 2 L4 d cos(pitch + omega).
            let cos_of = |r: f64| (d * d + l4 * l4 - r * r) / (2.0 * l4 * d);
            let (c_far, c_near) = (cos_of(far), cos_of(near.max(0.0)));
            if c_far > 1.0 || c_near < -1.0 {
                return None;
            }
            Some((c_near.min(1.0).acos(), c_far.max(-1.0).acos()))
        };
        Self {
            omega: h.atan2(plane.r),
            arcs: [arc(bends(0.0, PI)), arc(bends(-PI, 0.0))],
        }
    }

    /// Whether some branch may be possible at `pitch`.
    pub fn admit(&self, pitch: f64) -> bool {
        let u = crate::geometry::wrap_angle(pitch + self.omega).abs();
        self.arcs
            .iter()
            .flatten()
            .any(|&(a, b)| u >= a - 1e-9 && u <= b + 1e-9)
    }
}

/// A way chosen.
#[derive(Clone, Copy, Debug)]
pub(super) struct Chosen {
    pub joints: Joints,
    pub branch: Branch,
    pub manipulability: f64,
}

impl Chosen {
    /// The solution once refined to `(joints, iterations, residual)`: its manipulability
    /// measured afresh only when the refinement moved the joints.
    pub fn refined(
        self,
        cfg: &ArmConfig,
        (joints, iterations, residual): (Joints, u32, f64),
    ) -> Solution {
        let manipulability = if iterations == 0 {
            self.manipulability
        } else {
            manipulability(cfg, &joints)
        };
        Solution {
            joints,
            branch: self.branch,
            residual,
            manipulability,
            iterations,
        }
    }
}

/// Seed 000 section 4.2.3, made strict: of the possible ways, those at least
/// `min_manipulability` from a singularity; of those the nearest `current` by weighted
/// joint travel; a tie to the more manipulable.
pub(super) fn choose(
    cfg: &ArmConfig,
    ways: &[Way],
    current: &Joints,
) -> Option<Result<Chosen, f64>> {
    let mut best: Option<(f64, Chosen)> = None;
    let mut most_manipulable: Option<f64> = None;
    for way in ways.iter().filter(|w| w.possible()) {
        let mut joints = way.joints;
        for (i, j) in joints.iter_mut().enumerate() {
            *j = j.clamp(cfg.limits.min[i], cfg.limits.max[i]);
        }
        let joints = Joints(joints);
        let m = manipulability(cfg, &joints);
        most_manipulable = Some(most_manipulable.map_or(m, |b: f64| b.max(m)));
        if m < cfg.min_manipulability {
            continue;
        }
        let travel: f64 = (0..4)
            .map(|i| cfg.joint_weights[i] * (joints.0[i] - current.0[i]).abs())
            .sum();
        let better = match &best {
            None => true,
            Some((t, c)) => travel < *t - 1e-12 || (travel <= *t + 1e-12 && m > c.manipulability),
        };
        if better {
            best = Some((
                travel,
                Chosen {
                    joints,
                    branch: way.branch,
                    manipulability: m,
                },
            ));
        }
    }
    match (best, most_manipulable) {
        (Some((_, chosen)), _) => Some(Ok(chosen)),
        (None, Some(m)) => Some(Err(m)),
        (None, None) => None,
    }
}

/// The least and greatest distance from the shoulder to the wrist.
pub(super) fn wrist_reach(cfg: &ArmConfig) -> (f64, f64) {
    let [l2, l3, _] = cfg.links;
    ((l2 - l3).abs(), l2 + l3)
}

/// Why none of `ways` is possible: the wrist out of reach in every plane, else the way
/// nearest possible names the joint that stops it.
pub(super) fn refusal(cfg: &ArmConfig, ways: &[Way], pitch: f64) -> Unreachable {
    let (least, reach) = wrist_reach(cfg);
    let nearest = ways
        .iter()
        .filter(|w| w.wrist_reached)
        .max_by(|a, b| a.margin.total_cmp(&b.margin));
    match nearest {
        Some(way) => {
            let i = way.worst_joint;
            Unreachable::JointLimit {
                joint: i + 1,
                value: way.joints[i],
                min: cfg.limits.min[i],
                max: cfg.limits.max[i],
            }
        }
        None => {
            let outside = |d: f64| (d - reach).max(least - d);
            let distance = ways
                .iter()
                .map(|w| w.wrist)
                .min_by(|a, b| outside(*a).total_cmp(&outside(*b)))
                .unwrap_or(f64::NAN);
            Unreachable::PitchOutOfReach {
                pitch,
                distance,
                least,
                reach,
            }
        }
    }
}

/// The tool's distance from the shoulder, and the least and greatest the arm can span
/// (its links folded back on each other and stretched out).
pub(super) fn tool_reach(cfg: &ArmConfig, x: f64, y: f64, z: f64) -> (f64, f64, f64) {
    let [l2, l3, l4] = cfg.links;
    let longest = l2.max(l3).max(l4);
    let total = l2 + l3 + l4;
    let distance = (x.hypot(y)).hypot(z - cfg.base_height);
    (distance, (2.0 * longest - total).max(0.0), total)
}

/// `TooFar` or `TooClose` when the tool's distance from the shoulder rules the target
/// out at any pitch.
pub(super) fn out_of_span(cfg: &ArmConfig, x: f64, y: f64, z: f64) -> Result<(), Unreachable> {
    let (distance, least, reach) = tool_reach(cfg, x, y, z);
    if distance > reach + REACH_SLACK {
        return Err(Unreachable::TooFar { distance, reach });
    }
    if distance < least - REACH_SLACK {
        return Err(Unreachable::TooClose { distance, least });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn fit_turns_into_the_limits() {
        assert_eq!(fit(0.5, -1.0, 1.0).0, 0.5);
        assert!((fit(0.5 + TAU, -1.0, 1.0).0 - 0.5).abs() < 1e-12);
        let (v, m) = fit(3.0, -0.9 * PI, 0.9 * PI);
        assert_eq!(v, 3.0);
        assert!(m < 0.0);
    }

    #[test]
    fn right_angle_elbow_by_hand() {
        // Target x = 0.124, z = 0.057, tool down: the wrist is 0.150 above, at
        // (0.124, 0.130) from the shoulder, R^2 = 0.124^2 + 0.130^2 = L2^2 + L3^2, so the
        // interior angle is 90 degrees; phi1 = atan(0.124/0.130) + ... leaves the upper arm
        // vertical and the forearm level.
        let c = ArmConfig::default();
        let planes = planes(&c, 0.124, 0.0, 0.057, &Joints::default());
        let [up, down] = ways(&c, &planes[0], FRAC_PI_2);
        let lean = 0.024f64.atan2(0.128);
        let want = [0.0, -lean, lean, FRAC_PI_2];
        for (i, w) in want.iter().enumerate() {
            assert!((up.joints[i] - w).abs() < 1e-12, "{up:?}");
        }
        assert!(up.possible() && up.branch == Branch::ElbowUp);
        // Elbow down folds the elbow the way its limits forbid.
        assert!(!down.possible() && down.worst_joint == 2, "{down:?}");
    }
}
