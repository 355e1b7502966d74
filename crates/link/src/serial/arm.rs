//! A four-joint arm of hobby servos on a ROSArduinoBridge board: each joint's target
//! angle becomes one `s IDX DEG` servo write, sent only when it moved by a degree or more,
//! and the worker sends the waiting writes one per turn of its loop, between the wheels'.

use super::config::ArmServo;
use navdeck_core::data::ArmTarget;

/// The servo writes a target needs, and what to warn about.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Plan {
    /// (servo index, degrees 0..=180), base joint first.
    pub writes: Vec<(u8, u16)>,
    pub warnings: Vec<String>,
}

/// The arm's servos and the angle each was last sent for, degrees (before rounding).
#[derive(Clone, Debug)]
pub struct ArmServos {
    servos: Vec<ArmServo>,
    sent: [Option<f64>; 4],
    /// The last target was refused (said once until a good one comes).
    refusing: bool,
}

impl ArmServos {
    pub fn new(servos: &[ArmServo]) -> Self {
        Self {
            servos: servos.to_vec(),
            sent: [None; 4],
            refusing: false,
        }
    }

    /// Whether the robot has an arm (`[serial] arm_servos` lists four).
    pub fn configured(&self) -> bool {
        self.servos.len() == 4
    }

    /// The firmware may have reset (a reconnection): the next target is sent in full.
    pub fn forget(&mut self) {
        self.sent = [None; 4];
    }

    /// The writes that bring each servo to `target`: the angles clamped to the servo's
    /// 0..=180 degrees (with a warning), and only those that changed by a degree or more.
    pub fn plan(&mut self, target: &ArmTarget) -> Plan {
        let mut plan = Plan::default();
        if !self.configured() {
            return plan;
        }
        if let Some(k) = target.joints.iter().position(|j| !j.is_finite()) {
            if !std::mem::replace(&mut self.refusing, true) {
                plan.warnings.push(format!(
                    "arm target refused: joint {} = {}",
                    k + 1,
                    target.joints[k]
                ));
            }
            return plan;
        }
        self.refusing = false;
        for (k, (servo, joint)) in self.servos.iter().zip(target.joints).enumerate() {
            // Radians to degrees (x 180/π), then the servo's zero and mounting sign.
            let wanted = servo.zero_deg + servo.direction as f64 * joint.to_degrees();
            let clamped = wanted.clamp(0.0, 180.0);
            // Compared before rounding: a joint wavering across a half degree stays put.
            if self.sent[k].is_some_and(|last| (clamped - last).abs() < 1.0) {
                continue;
            }
            if !(0.0..=180.0).contains(&wanted.round()) {
                plan.warnings.push(format!(
                    "arm joint {} asks servo {} for {wanted:.0} degrees: clamped to {clamped:.0}",
                    k + 1,
                    servo.index
                ));
            }
            self.sent[k] = Some(clamped);
            // The config check keeps the index within 0..=15.
            plan.writes
                .push((servo.index as u8, clamped.round() as u16));
        }
        plan
    }
}

/// Servo writes waiting for the port, oldest first; a newer write to the same servo
/// replaces the waiting one.
#[derive(Clone, Debug, Default)]
pub struct ServoQueue {
    waiting: Vec<(u8, u16)>,
}

impl ServoQueue {
    pub fn push(&mut self, writes: &[(u8, u16)]) {
        for &(index, deg) in writes {
            match self.waiting.iter_mut().find(|(i, _)| *i == index) {
                Some(w) => w.1 = deg,
                None => self.waiting.push((index, deg)),
            }
        }
    }

    pub fn pop(&mut self) -> Option<(u8, u16)> {
        (!self.waiting.is_empty()).then(|| self.waiting.remove(0))
    }

    pub fn is_empty(&self) -> bool {
        self.waiting.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_4;

    fn servos() -> Vec<ArmServo> {
        [(4, 90.0, 1), (5, 90.0, -1), (6, 30.0, 1), (7, 150.0, -1)]
            .map(|(index, zero_deg, direction)| ArmServo {
                index,
                zero_deg,
                direction,
            })
            .to_vec()
    }

    fn target(joints: [f64; 4]) -> ArmTarget {
        ArmTarget {
            joints,
            within: 1.0,
        }
    }

    #[test]
    fn each_joint_goes_to_its_servo_with_zero_and_direction() {
        let mut arm = ArmServos::new(&servos());
        let plan = arm.plan(&target([FRAC_PI_4, FRAC_PI_4, -0.5, 0.0]));
        // 45° on each: 90 + 45, 90 - 45; -0.5 rad = -28.65°: 30 - 28.65; 150 - 0.
        assert_eq!(plan.writes, vec![(4, 135), (5, 45), (6, 1), (7, 150)]);
        assert!(plan.warnings.is_empty(), "{:?}", plan.warnings);
    }

    #[test]
    fn only_joints_that_moved_a_degree_are_written_again() {
        let mut arm = ArmServos::new(&servos());
        arm.plan(&target([0.0; 4]));
        let nudge = 0.6f64.to_radians();
        let plan = arm.plan(&target([nudge, 0.0, 2.0f64.to_radians(), 0.0]));
        assert_eq!(plan.writes, vec![(6, 32)]);
        arm.forget();
        assert_eq!(arm.plan(&target([0.0; 4])).writes.len(), 4);
    }

    #[test]
    fn angles_beyond_the_servo_are_clamped_with_a_warning() {
        let mut arm = ArmServos::new(&servos());
        let plan = arm.plan(&target([2.0, 0.0, -1.0, 0.0]));
        // 90 + 114.6 = 204.6 -> 180; 30 - 57.3 = -27.3 -> 0.
        assert_eq!(plan.writes, vec![(4, 180), (5, 90), (6, 0), (7, 150)]);
        assert_eq!(plan.warnings.len(), 2, "{:?}", plan.warnings);
        assert!(plan.warnings[0].contains("joint 1") && plan.warnings[0].contains("205"));
        assert!(arm.plan(&target([2.0, 0.0, -1.0, 0.0])) == Plan::default());
        let bad = arm.plan(&target([f64::NAN, 0.0, 0.0, 0.0]));
        assert!(bad.writes.is_empty() && bad.warnings[0].contains("NaN"));
        assert_eq!(arm.plan(&target([f64::NAN; 4])), Plan::default());
    }

    #[test]
    fn a_newer_write_replaces_the_waiting_one_for_its_servo() {
        let mut q = ServoQueue::default();
        q.push(&[(4, 10), (5, 20)]);
        q.push(&[(4, 30), (6, 40)]);
        assert_eq!(q.pop(), Some((4, 30)));
        assert_eq!(q.pop(), Some((5, 20)));
        assert_eq!(q.pop(), Some((6, 40)));
        assert!(q.is_empty() && q.pop().is_none());
    }
}
