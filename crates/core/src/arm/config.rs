//! The `[arm]` config section: the 4-DOF arm's geometry, limits, mount, solver and named
//! poses. No `[arm]` in a config file, no arm.
//!
//! Defaults: geometry from seed 000 section 4.1.1 (its DH table); where the seed gives
//! symbols but no numbers (joint offsets, joint limits, speeds, gripper, poses, mount) the
//! values are OpenManipulator-X's (ROBOTIS `open_manipulator_description`
//! open_manipulator.urdf.xacro, `open_manipulator_x.srdf`, and TurtleBot3 manipulation's
//! `base_fixed` joint), the arm seed 000 drives; each field says which.

use serde::{Deserialize, Serialize};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Which inverse kinematics `arm::inverse` runs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Solver {
    /// Seed 000 section 4.2: closed form for all four joints (the tool's pitch asked, or
    /// chosen), damped-least-squares refinement (section 4.3.2).
    #[default]
    #[serde(rename = "4dof")]
    FourDof,
    /// Seed 002's constrained IK: shoulder and elbow solved in the arm's plane; the wrist
    /// is slaved so the tool keeps `fixed_pitch`; the base yaw points the plane at the
    /// target. See `arm::ik_2dof`.
    #[serde(rename = "2dof")]
    TwoDof,
}

/// Per-joint limits, joint 1 (base yaw) to joint 4 (wrist pitch).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct JointLimits {
    /// Least angle of each joint, rad.
    pub min: [f64; 4],
    /// Greatest angle of each joint, rad.
    pub max: [f64; 4],
    /// Top speed of each joint, rad/s.
    pub speed: [f64; 4],
}

impl Default for JointLimits {
    fn default() -> Self {
        // The seed names joint limits without numbers (section 4.2.2 `self.joint_limits`):
        // OpenManipulator-X's URDF, -0.9pi..0.9pi, -0.57pi..0.5pi, -0.3pi..0.44pi,
        // -0.57pi..0.65pi, each at 4.8 rad/s.
        Self {
            min: [-0.9 * PI, -0.57 * PI, -0.3 * PI, -0.57 * PI],
            max: [0.9 * PI, 0.5 * PI, 0.44 * PI, 0.65 * PI],
            speed: [4.8; 4],
        }
    }
}

/// Where the arm's base frame (on joint 1's axis, z = 0 where `base_height` starts) sits
/// in the robot's `base_link`: metres and radians.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Mount {
    pub x: f64,
    pub y: f64,
    pub z: f64,
    pub yaw: f64,
}

impl Default for Mount {
    fn default() -> Self {
        // TurtleBot3 manipulation's base_fixed joint puts OpenManipulator-X's link1 at
        // (-0.092, 0, 0.091) in base_link; joint 1's axis is 0.012 m ahead of link1.
        Self {
            x: -0.092 + 0.012,
            y: 0.0,
            z: 0.091,
            yaw: 0.0,
        }
    }
}

impl Mount {
    /// A point in the arm's base frame, in `base_link`.
    pub fn to_robot(&self, p: [f64; 3]) -> [f64; 3] {
        let (s, c) = self.yaw.sin_cos();
        [
            self.x + c * p[0] - s * p[1],
            self.y + s * p[0] + c * p[1],
            self.z + p[2],
        ]
    }

    /// A point in `base_link`, in the arm's base frame.
    pub fn from_robot(&self, p: [f64; 3]) -> [f64; 3] {
        let (s, c) = self.yaw.sin_cos();
        let (dx, dy) = (p[0] - self.x, p[1] - self.y);
        [c * dx + s * dy, -s * dx + c * dy, p[2] - self.z]
    }
}

/// Seed 000 section 4.3.2's damped-least-squares refinement.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Refine {
    /// Damping factor lambda in J^T (J J^T + lambda^2 I)^-1 (seed 000: 0.01).
    pub damping: f64,
    /// Steps at most (seed 000 section 4.4.2's finest level, "ultra_fine": 20).
    pub max_iterations: u32,
    /// Stop once the tool is this close to the target, metres (navdeck's bar, 1e-6 m; the
    /// seed's finest is 1e-5).
    pub tolerance: f64,
}

impl Default for Refine {
    fn default() -> Self {
        Self {
            damping: 0.01,
            max_iterations: 20,
            tolerance: 1e-6,
        }
    }
}

/// Gripper widths, metres between the fingers' frames.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct GripperWidths {
    pub open: f64,
    pub closed: f64,
}

impl Default for GripperWidths {
    fn default() -> Self {
        // OpenManipulator-X: fingers 0.021 m either side of the middle, each moving
        // -0.010..0.019 m (its srdf's "close" and "open"): 2 x (0.021 + q).
        Self {
            open: 2.0 * (0.021 + 0.019),
            closed: 2.0 * (0.021 - 0.010),
        }
    }
}

/// Named joint vectors, radians, joint 1 to 4.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct NamedPoses {
    /// OpenManipulator-X's srdf "home".
    pub home: [f64; 4],
    /// OpenManipulator-X's srdf "init": all zeros, the arm stretched forward.
    pub ready: [f64; 4],
    /// TurtleBot3 manipulation's srdf "init_pose": folded over the robot (its -1.5707 as
    /// -pi/2).
    pub stow: [f64; 4],
}

impl Default for NamedPoses {
    fn default() -> Self {
        Self {
            home: [0.0, -1.0, 0.7, 0.3],
            ready: [0.0; 4],
            stow: [0.0, -FRAC_PI_2, 1.37, 0.2258],
        }
    }
}

/// The `[arm]` section.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ArmConfig {
    /// `"4dof"` or `"2dof"`.
    pub solver: Solver,
    /// Height of the shoulder (joint 2's axis) above the arm's base frame, m (seed 000
    /// DH d1 = 0.077).
    pub base_height: f64,
    /// Upper arm, forearm, wrist-to-tool lengths, m (seed 000 DH a2, a3, a4: 0.130,
    /// 0.124, 0.150).
    pub links: [f64; 3],
    /// theta_i,offset of seed 000's DH table, rad: link i's angle is theta_i + offset_i.
    /// The seed gives no numbers; its a2 = 0.130 m is OpenManipulator-X's 0.128 m x
    /// 0.024 m L-shaped upper arm, so at joint zero the upper arm leans
    /// atan2(0.024, 0.128) forward of vertical and the forearm is level:
    /// offsets 0, -(pi/2 - atan2(0.024, 0.128)), +(pi/2 - atan2(0.024, 0.128)), 0.
    pub joint_offsets: [f64; 4],
    pub limits: JointLimits,
    /// Weights of each joint's travel when choosing the solution nearest the current
    /// joints (seed 000 section 4.2.3 sums |delta theta| unweighted: all 1).
    pub joint_weights: [f64; 4],
    /// 4dof without a pitch asked: the tool pitch preferred, rad (seed 000 section
    /// 4.2.2's target_orientation = pi/2, the tool pointing straight down).
    pub preferred_pitch: f64,
    /// 2dof: the pitch the tool keeps, rad (seed 002 gives none: navdeck's choice, pi/2,
    /// straight down as seed 000 prefers).
    pub fixed_pitch: f64,
    /// Refuse solutions whose manipulability sqrt(det(J J^T)) (position rows, m^3) is
    /// below this; 0 refuses none (navdeck's default: seed 000's 0.01 only flags
    /// "near singularity", in units it does not state).
    pub min_manipulability: f64,
    pub refine: Refine,
    pub mount: Mount,
    pub gripper: GripperWidths,
    pub poses: NamedPoses,
}

impl Default for ArmConfig {
    fn default() -> Self {
        let lean = FRAC_PI_2 - 0.024f64.atan2(0.128);
        Self {
            solver: Solver::FourDof,
            base_height: 0.077,
            links: [0.130, 0.124, 0.150],
            joint_offsets: [0.0, -lean, lean, 0.0],
            limits: JointLimits::default(),
            joint_weights: [1.0; 4],
            preferred_pitch: FRAC_PI_2,
            fixed_pitch: FRAC_PI_2,
            min_manipulability: 0.0,
            refine: Refine::default(),
            mount: Mount::default(),
            gripper: GripperWidths::default(),
            poses: NamedPoses::default(),
        }
    }
}

/// The shortest link accepted, m: a link under a centimetre is no link (the smallest
/// hobby servo, an SG90, is 23 mm across), and shorter ones leave the arm's Jacobian
/// numerically singular everywhere.
pub const MIN_LINK: f64 = 0.01;
/// The longest link accepted, m: beyond this a value is surely a typo (mm for m).
pub const MAX_LINK: f64 = 2.0;
/// The highest shoulder accepted above the arm's base frame, m (a typo beyond).
pub const MAX_BASE_HEIGHT: f64 = 1.0;
/// No arm navdeck accepts reaches farther from its base frame than this, m: the highest
/// shoulder plus three of the longest links. Targets beyond it are refused as typos.
pub const FARTHEST_REACH: f64 = MAX_BASE_HEIGHT + 3.0 * MAX_LINK;
/// The slowest joint speed accepted, rad/s: below the smallest speed a servo can be
/// commanded (Dynamixel XM430's profile-velocity unit is 0.229 rev/min = 0.024 rad/s), and
/// slow enough that a move across a whole turn would take over ten minutes.
pub const MIN_JOINT_SPEED: f64 = 0.01;
/// The fastest joint speed accepted, rad/s: ten times a hobby servo's no-load speed
/// (XM430-W350: 46 rev/min = 4.8 rad/s); beyond it a value is surely a typo.
pub const MAX_JOINT_SPEED: f64 = 50.0;
/// The longest move a valid config can ask, s: a whole turn (the widest span
/// `validate` allows a joint) at the slowest speed. Motion loops stop at this bound.
pub const LONGEST_MOVE: f64 = TAU / MIN_JOINT_SPEED;
/// The largest joint weight, relative to the others (only their ratios matter; this keeps
/// the weighted travel finite).
const MAX_JOINT_WEIGHT: f64 = 1000.0;

/// "field[0]" to "field[3]": names for each element of the section's arrays (the check
/// names a field).
macro_rules! four {
    ($field:literal) => {
        [
            concat!($field, "[0]"),
            concat!($field, "[1]"),
            concat!($field, "[2]"),
            concat!($field, "[3]"),
        ]
    };
}

const LINKS: [&str; 3] = ["links[0]", "links[1]", "links[2]"];
const OFFSETS: [&str; 4] = four!("joint_offsets");
const MIN: [&str; 4] = four!("limits.min");
const MAX: [&str; 4] = four!("limits.max");
const SPEED: [&str; 4] = four!("limits.speed");
const WEIGHTS: [&str; 4] = four!("joint_weights");
const POSES: [(&str, [&str; 4]); 3] = [
    ("home", four!("poses.home")),
    ("ready", four!("poses.ready")),
    ("stow", four!("poses.stow")),
];

impl ArmConfig {
    /// A named pose's joints: `home`, `ready` or `stow`.
    pub fn pose(&self, name: &str) -> Option<super::Joints> {
        match name {
            "home" => Some(super::Joints(self.poses.home)),
            "ready" => Some(super::Joints(self.poses.ready)),
            "stow" => Some(super::Joints(self.poses.stow)),
            _ => None,
        }
    }

    /// Checks values a parser cannot: (field, value, reason) for the first bad one.
    pub fn validate(&self) -> Result<(), crate::data::check::Invalid> {
        use crate::data::check::{counts_within, within};
        use crate::data::number::short;
        within(&[("base_height", self.base_height, 0.0, MAX_BASE_HEIGHT)])?;
        for (name, v) in LINKS.iter().zip(self.links) {
            within(&[(name, v, MIN_LINK, MAX_LINK)])?;
        }
        for i in 0..4 {
            within(&[
                (OFFSETS[i], self.joint_offsets[i], -TAU, TAU),
                (MIN[i], self.limits.min[i], -TAU, TAU),
                (MAX[i], self.limits.max[i], -TAU, TAU),
            ])?;
            let (lo, hi) = (self.limits.min[i], self.limits.max[i]);
            if lo > hi {
                let reason = format!("is below limits.min ({})", short(lo));
                return Err((MAX[i], hi, reason.into()));
            }
            if hi - lo > TAU {
                let reason = format!("spans more than a turn from limits.min ({})", short(lo));
                return Err((MAX[i], hi, reason.into()));
            }
            within(&[
                (
                    SPEED[i],
                    self.limits.speed[i],
                    MIN_JOINT_SPEED,
                    MAX_JOINT_SPEED,
                ),
                (WEIGHTS[i], self.joint_weights[i], 0.0, MAX_JOINT_WEIGHT),
            ])?;
        }
        within(&[
            ("preferred_pitch", self.preferred_pitch, -TAU, TAU),
            ("fixed_pitch", self.fixed_pitch, -TAU, TAU),
            ("min_manipulability", self.min_manipulability, 0.0, 1.0),
            ("refine.damping", self.refine.damping, 0.0, 1.0),
            ("refine.tolerance", self.refine.tolerance, 1e-12, 0.01),
            ("mount.x", self.mount.x, -10.0, 10.0),
            ("mount.y", self.mount.y, -10.0, 10.0),
            ("mount.z", self.mount.z, -10.0, 10.0),
            ("mount.yaw", self.mount.yaw, -TAU, TAU),
            ("gripper.open", self.gripper.open, 0.0, 1.0),
            ("gripper.closed", self.gripper.closed, 0.0, 1.0),
        ])?;
        counts_within(&[(
            "refine.max_iterations",
            u64::from(self.refine.max_iterations),
            0,
            10_000,
        )])?;
        if self.gripper.closed > self.gripper.open {
            return Err((
                "gripper.closed",
                self.gripper.closed,
                format!("is wider than gripper.open ({})", short(self.gripper.open)).into(),
            ));
        }
        for (pose, names) in POSES {
            let joints = self.pose(pose).map(|j| j.0).unwrap_or_default();
            for i in 0..4 {
                // Named with the limits that bound it: changing a limit may be what
                // left a pose outside.
                within(&[(names[i], joints[i], self.limits.min[i], self.limits.max[i])]).map_err(
                    |(field, value, reason)| {
                        (
                            field,
                            value,
                            format!("{reason} (limits.min[{i}]..=limits.max[{i}])").into(),
                        )
                    },
                )?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_seed_000_and_valid() {
        let c = ArmConfig::default();
        assert_eq!(c.validate(), Ok(()));
        assert_eq!(c.base_height, 0.077);
        assert_eq!(c.links, [0.130, 0.124, 0.150]);
        // pi/2 - atan2(0.024, 0.128) = 1.3854 rad (79.4 degrees).
        assert!((c.joint_offsets[2] - 1.385448).abs() < 1e-6);
        assert_eq!(c.joint_offsets[1], -c.joint_offsets[2]);
        assert!((c.gripper.open - 0.080).abs() < 1e-12);
        assert!((c.gripper.closed - 0.022).abs() < 1e-12);
    }

    #[test]
    fn bad_values_are_named() {
        let bad = |f: fn(&mut ArmConfig)| {
            let mut c = ArmConfig::default();
            f(&mut c);
            c.validate().unwrap_err()
        };
        assert_eq!(bad(|c| c.links[1] = 0.0).0, "links[1]");
        assert_eq!(bad(|c| c.links[2] = -0.1).0, "links[2]");
        assert_eq!(bad(|c| c.base_height = f64::NAN).0, "base_height");
        assert_eq!(
            bad(|c| c.joint_offsets[3] = f64::INFINITY).0,
            "joint_offsets[3]"
        );
        let (field, value, reason) = bad(|c| {
            c.limits.min[2] = 1.0;
            c.limits.max[2] = 0.5;
        });
        assert_eq!((field, value), ("limits.max[2]", 0.5));
        assert!(reason.contains("below"), "{reason}");
        assert_eq!(bad(|c| c.limits.speed[0] = 0.0).0, "limits.speed[0]");
        assert_eq!(bad(|c| c.mount.yaw = f64::NAN).0, "mount.yaw");
        assert_eq!(bad(|c| c.poses.stow[1] = 3.0).0, "poses.stow[1]");
        assert_eq!(bad(|c| c.gripper.closed = 0.5).0, "gripper.closed");
        assert_eq!(bad(|c| c.refine.tolerance = 0.0).0, "refine.tolerance");
    }

    #[test]
    fn links_speeds_and_weights_are_bounded_on_both_sides() {
        let bad = |f: fn(&mut ArmConfig)| {
            let mut c = ArmConfig::default();
            f(&mut c);
            c.validate().unwrap_err()
        };
        let (field, value, reason) = bad(|c| c.links[0] = 1e-300);
        assert_eq!((field, value), ("links[0]", 1e-300));
        assert_eq!(reason, "must lie in 0.01..=2");
        assert_eq!(bad(|c| c.links[2] = 1e308).0, "links[2]");
        let (field, _, reason) = bad(|c| c.limits.speed[3] = 1e-6);
        assert_eq!(field, "limits.speed[3]");
        assert_eq!(reason, "must lie in 0.01..=50");
        assert_eq!(bad(|c| c.limits.speed[1] = 1e308).0, "limits.speed[1]");
        assert_eq!(bad(|c| c.joint_weights[2] = 1e308).0, "joint_weights[2]");
        // The slowest valid arm still crosses its widest joint within LONGEST_MOVE.
        let mut slow = ArmConfig::default();
        slow.limits.speed = [MIN_JOINT_SPEED; 4];
        assert_eq!(slow.validate(), Ok(()));
        let far = crate::arm::move_time(
            &slow,
            &crate::arm::Joints(slow.limits.min),
            &crate::arm::Joints(slow.limits.max),
        );
        assert!(far <= LONGEST_MOVE, "{far}");
    }

    #[test]
    fn toml_names_only_what_it_changes_and_refuses_unknown_fields() {
        let c: ArmConfig =
            toml::from_str("solver = \"2dof\"\n[limits]\nspeed = [1.0, 1.0, 1.0, 1.0]\n").unwrap();
        assert_eq!(c.solver, Solver::TwoDof);
        assert_eq!(c.limits.speed, [1.0; 4]);
        assert_eq!(c.limits.min, JointLimits::default().min);
        assert!(toml::from_str::<ArmConfig>("link = [0.1, 0.1, 0.1]").is_err());
        assert!(toml::from_str::<ArmConfig>("solver = \"3dof\"").is_err());
        assert!(toml::from_str::<ArmConfig>("[mount]\nroll = 0.0").is_err());
    }

    #[test]
    fn mount_round_trips_a_point() {
        let m = Mount {
            x: 0.1,
            y: -0.2,
            z: 0.3,
            yaw: 0.7,
        };
        let p = [0.25, 0.05, -0.1];
        let back = m.from_robot(m.to_robot(p));
        for i in 0..3 {
            assert!((back[i] - p[i]).abs() < 1e-12);
        }
        // Default: the arm's origin 0.080 m behind base_link's and 0.091 m above it.
        let d = Mount::default().to_robot([0.0; 3]);
        assert!((d[0] + 0.080).abs() < 1e-12 && (d[2] - 0.091).abs() < 1e-12);
    }
}
