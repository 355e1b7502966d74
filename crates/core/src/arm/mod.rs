//! The 4-DOF arm's kinematics (seed 000 section 4; seed 002's constrained variant): pure
//! functions of an `ArmConfig`, reading no clock.
//!
//! Frames and angles. The arm's base frame has x forward, y left, z up (REP-103), its
//! origin on joint 1's axis, `base_height` below the shoulder; `Mount` places it in the
//! robot's `base_link`. Joint 1 turns the arm about z (positive to the left); joints 2, 3
//! and 4 turn about the arm's y axis, positive tipping forward and down, as
//! OpenManipulator-X's joints do. A tool pitch is REP-103's: 0 points the tool level
//! and forward, +pi/2 straight down. Link i+1 points along the sum of joints 2..=i plus
//! their offsets (seed 000 DH theta_i + theta_i,offset).
//!
//! With the default limits the elbow only bends one way (joint 3 + its offset stays in
//! 0.44..2.77 rad), so every in-limit solution is `ElbowUp`; `ElbowDown` solutions are
//! considered and refused by the limits, and found by a config whose limits allow them.

pub mod config;
mod ik_2dof;
mod ik_4dof;
pub mod kinematics;
mod planar;
mod refine;

#[cfg(test)]
mod bars;

pub use config::{ArmConfig, Solver};
pub use kinematics::{
    check_limits, forward, inverse, jacobian, manipulability, move_time, near_singular,
};

use crate::data::number::{distinct, fixed};
use serde::{Deserialize, Serialize};

/// Joint angles, radians: joint 1 (base yaw), 2 (shoulder), 3 (elbow), 4 (wrist pitch).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Joints(pub [f64; 4]);

/// Where the tool is, in the arm's base frame: metres, and its pitch in radians.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ToolPose {
    pub x: f64,
    pub y: f64,
    pub z: f64,
    pub pitch: f64,
}

/// What the tool should reach: a point in the arm's base frame, with a pitch or, without
/// one, the pitch the solver prefers (4dof) or keeps (2dof).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Target {
    pub x: f64,
    pub y: f64,
    pub z: f64,
    pub pitch: Option<f64>,
}

impl Target {
    /// A point, the pitch left to the solver.
    pub fn point(x: f64, y: f64, z: f64) -> Self {
        Self {
            x,
            y,
            z,
            pitch: None,
        }
    }
}

impl From<ToolPose> for Target {
    fn from(p: ToolPose) -> Self {
        Self {
            x: p.x,
            y: p.y,
            z: p.z,
            pitch: Some(p.pitch),
        }
    }
}

/// Which side of the shoulder-to-wrist line the elbow is on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Branch {
    /// The elbow above the line from shoulder to wrist.
    ElbowUp,
    /// The elbow below it.
    ElbowDown,
}

impl std::fmt::Display for Branch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Branch::ElbowUp => "elbow up",
            Branch::ElbowDown => "elbow down",
        })
    }
}

/// A solved target.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Solution {
    /// Within every joint's limits.
    pub joints: Joints,
    pub branch: Branch,
    /// Distance from the tool at `joints` (forward kinematics) to the target, metres.
    pub residual: f64,
    /// sqrt(det(J J^T)) of the position rows of the Jacobian at `joints`, m^3 (seed 000
    /// section 4.1.2); 0 at a singularity.
    pub manipulability: f64,
    /// Refinement steps taken after the closed form (0: it was already within the
    /// tolerance).
    pub iterations: u32,
}

/// Why a target cannot be reached. Joints are numbered from 1 (the base) to 4 (the
/// wrist); angles are radians, shown in degrees. Two numbers a message compares are
/// printed with enough decimals to differ (`data::number::distinct`).
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum Unreachable {
    #[error("{}", beyond("the arm reaches", *distance, *reach))]
    TooFar { distance: f64, reach: f64 },
    #[error("{}", beyond("the arm reaches no closer than", *distance, *least))]
    TooClose { distance: f64, least: f64 },
    /// Within the span of the stretched and folded arm, yet no pitch of the tool puts the
    /// wrist where shoulder and elbow reach within their limits.
    #[error(
        "target {} m from the shoulder is within the arm's span ({} to {} m), but no tool pitch reaches it within the joint limits",
        fixed(*distance, 3), fixed(*least, 3), fixed(*reach, 3)
    )]
    NoPitch {
        distance: f64,
        least: f64,
        reach: f64,
    },
    #[error("{}", pitch_out_of_reach(*pitch, *distance, *least, *reach))]
    PitchOutOfReach {
        pitch: f64,
        distance: f64,
        least: f64,
        reach: f64,
    },
    #[error("{}", joint_limit(*joint, *value, *min, *max))]
    JointLimit {
        joint: usize,
        value: f64,
        min: f64,
        max: f64,
    },
    #[error(
        "every solution is too near a singularity: manipulability {manipulability:.2e} m^3 is below min_manipulability"
    )]
    Singular { manipulability: f64 },
    #[error("{field} is not a finite number")]
    NotANumber { field: &'static str },
    #[error(
        "the 2dof solver keeps the tool at pitch {} deg; {} deg was asked",
        fixed(locked.to_degrees(), 1), fixed(asked.to_degrees(), 1)
    )]
    PitchLocked { asked: f64, locked: f64 },
}

/// "target 0.500 m from the shoulder, the arm reaches 0.404 m".
fn beyond(what: &str, distance: f64, bound: f64) -> String {
    let (d, b) = distinct(distance, bound, 3);
    format!("target {d} m from the shoulder, {what} {b} m")
}

fn pitch_out_of_reach(pitch: f64, distance: f64, least: f64, reach: f64) -> String {
    let nearer = if distance > reach { reach } else { least };
    let (d, _) = distinct(distance, nearer, 3);
    format!(
        "with the tool at pitch {} deg the wrist would be {d} m from the shoulder; shoulder and elbow reach {} to {} m (another pitch may reach the target)",
        fixed(pitch.to_degrees(), 1),
        fixed(least, 3),
        fixed(reach, 3)
    )
}

fn joint_limit(joint: usize, value: f64, min: f64, max: f64) -> String {
    let nearer = if value > max { max } else { min };
    let (v, _) = distinct(value.to_degrees(), nearer.to_degrees(), 1);
    let (lo, hi) = (min.to_degrees(), max.to_degrees());
    let (lo, hi) = if value > max {
        (fixed(lo, 1), distinct(value.to_degrees(), hi, 1).1)
    } else {
        (distinct(value.to_degrees(), lo, 1).1, fixed(hi, 1))
    };
    format!("joint {joint} would have to turn to {v} deg, outside its limits {lo} to {hi} deg")
}
