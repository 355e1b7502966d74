//! What crosses a link about an arm: the joint positions the console asks for and the
//! ones the robot reports (radians, joint 1 the base, 4 the wrist; REP-103 units).

/// Joints an arm of four should move to, radians, and how long the move should take
/// (seconds: the joint speed limits' doing; a trajectory's `time_from_start`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ArmTarget {
    pub joints: [f64; 4],
    pub within: f64,
}

/// An arm's joints as last measured, radians.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ArmState {
    pub joints: [f64; 4],
}
