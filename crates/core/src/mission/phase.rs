//! What the mission is doing: its phases, what exploration is heading for, and why it
//! handed the robot to manual control.

use super::delivery::Delivery;
use super::drive::Turn;
use super::leg::Leg;
use super::pickup::Pickup;

/// What exploration is heading for.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Target {
    Frontier,
    /// Free space the camera has not looked at yet.
    Unseen,
    Marker(u32),
    /// A block seen by one marker only (odd marker).
    Potential(u32),
    /// An unexplained small object (index into `Mission::unexplained`).
    Object(usize),
    /// Back where the mission started, out of a fleet's way, once it has nothing left.
    Home,
}

#[derive(Clone, Debug)]
pub(super) enum Phase {
    /// Before the first step.
    Start,
    Scan {
        turn: Turn,
        initial: bool,
    },
    Choose,
    Explore {
        leg: Leg,
        target: Target,
    },
    /// Seed 001 "Robot Lost": rotating until a marker comes into view, since the time
    /// given; after `lost_timeout` without markers, driving back towards the nearest
    /// landmark known (navdeck's).
    Lost(f64, Option<Leg>),
    /// Backing away from a block the approach lost sight of (the robot may stand in its
    /// lethal ring, facing it), since the time given; then choosing again.
    BackOff(f64),
    Pickup(Pickup),
    Deliver(Delivery),
    /// A block is there to pick up, nothing is left to explore, and the arm does not
    /// answer (seed 000 §7.2.1: skip manipulation): standing still until it does.
    WaitArm,
    Done,
    Manual,
}

/// Why a mission handed the robot to manual control.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Cause {
    /// A goal it needed had no path, after every retry.
    Unreachable,
    /// No landmarks for `lost_timeout`.
    Lost,
    /// A block could not be picked up (no path to it, or the gripper kept missing).
    Pickup,
    /// A held block could not be delivered (no path to its gate).
    Delivery,
    /// Exploration was complete with found blocks left (their gate never seen).
    BlocksLeft,
    /// A block was picked up for a gate whose every drop place is taken, or where none
    /// left would surely count.
    GateFull,
}

impl Cause {
    pub fn label(self) -> &'static str {
        match self {
            Cause::Unreachable => "unreachable target",
            Cause::Lost => "lost",
            Cause::Pickup => "pickup failed",
            Cause::Delivery => "delivery failed",
            Cause::BlocksLeft => "blocks left without a gate",
            Cause::GateFull => "gate full",
        }
    }
}
