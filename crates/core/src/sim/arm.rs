//! The twin's arm: four joints that move towards the asked positions no faster than their
//! speed limits allow (seed 000's arm is position-controlled servos; a servo at its speed
//! limit moves at that speed), reported back as joint states, and the tool's place by
//! forward kinematics, where the gripper catches and lets go of blocks.

use crate::arm::{ArmConfig, Joints, forward};
use crate::data::{ArmState, ArmTarget};

/// The jaws catch a block whose centre is within its half side plus this of the tool
/// tip, across and in height (navdeck's choice: 1 cm).
pub const GRASP_TOLERANCE: f64 = 0.01;

/// See the module comment.
#[derive(Clone, Debug, PartialEq)]
pub struct TwinArm {
    config: ArmConfig,
    joints: [f64; 4],
    target: [f64; 4],
    /// Joint speed limits, rad/s.
    speed: [f64; 4],
}

impl TwinArm {
    /// The arm of `config` at rest in its home pose.
    pub fn new(config: &ArmConfig) -> Self {
        let joints = config.poses.home;
        Self {
            config: config.clone(),
            joints,
            target: joints,
            speed: config.limits.speed,
        }
    }

    /// The tool tip in the robot's frame (`base_link`, which the twin puts on the floor):
    /// x, y, z metres.
    pub fn tool_in_robot(&self) -> [f64; 3] {
        let t = forward(&self.config, &Joints(self.joints));
        self.config.mount.to_robot([t.x, t.y, t.z])
    }

    /// Asks for new joint positions; a target that is not finite is ignored.
    pub fn command(&mut self, target: &ArmTarget) {
        if target.joints.iter().all(|j| j.is_finite()) {
            self.target = target.joints;
        }
    }

    /// Moves every joint towards its target by at most its speed times `dt`.
    pub fn step(&mut self, dt: f64) {
        for k in 0..4 {
            let gap = self.target[k] - self.joints[k];
            let most = self.speed[k] * dt;
            self.joints[k] += gap.clamp(-most, most);
        }
    }

    pub fn joints(&self) -> [f64; 4] {
        self.joints
    }

    pub fn state(&self) -> ArmState {
        ArmState {
            joints: self.joints,
        }
    }

    /// Whether every joint has reached its target.
    pub fn settled(&self) -> bool {
        (0..4).all(|k| (self.target[k] - self.joints[k]).abs() < 1e-9)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn joints_move_at_their_speed_limits_and_stop_on_target() {
        let mut config = ArmConfig::default();
        config.poses.home = [0.0; 4];
        config.limits.speed = [1.0, 2.0, 0.5, 1.0];
        let mut arm = TwinArm::new(&config);
        arm.command(&ArmTarget {
            joints: [0.3, -0.3, 0.3, 0.0],
            within: 0.0,
        });
        arm.step(0.1);
        let j = arm.joints();
        assert!((j[0] - 0.1).abs() < 1e-12 && (j[1] + 0.2).abs() < 1e-12);
        assert!((j[2] - 0.05).abs() < 1e-12 && j[3] == 0.0);
        for _ in 0..10 {
            arm.step(0.1);
        }
        assert!(arm.settled());
        assert_eq!(arm.joints(), [0.3, -0.3, 0.3, 0.0]);
        // A target with NaN leaves the arm where it was going.
        arm.command(&ArmTarget {
            joints: [f64::NAN, 0.0, 0.0, 0.0],
            within: 0.0,
        });
        arm.step(1.0);
        assert_eq!(arm.joints(), [0.3, -0.3, 0.3, 0.0]);
    }
}
