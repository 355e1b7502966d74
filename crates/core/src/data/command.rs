//! What the console asks of the robot.

use crate::geometry::Twist;
use serde::{Deserialize, Serialize};

/// What the console asks of the robot for the next control period.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Command {
    pub twist: Twist,
    /// `Some` to move the gripper; `None` leaves it as it is.
    pub gripper: Option<GripperCommand>,
    /// `Some` to move an arm's joints there; `None` leaves the arm as it is.
    pub arm: Option<super::ArmTarget>,
}

impl Command {
    pub const STOP: Command = Command {
        twist: Twist::ZERO,
        gripper: None,
        arm: None,
    };
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GripperCommand {
    Open,
    Close,
}
