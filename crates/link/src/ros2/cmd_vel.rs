//! When to put a velocity on cmd_vel: every control step while moving, a few zeros when
//! the robot stops, then silence, so that an idle navdeck does not drown other cmd_vel
//! sources (a joystick, Nav2) in zeros.

use navdeck_core::geometry::Twist;

/// Zero twists sent on each stop: a lost one would leave the robot moving.
pub const ZERO_REPEATS: u32 = 3;

#[derive(Clone, Debug, Default)]
pub struct CmdVelPolicy {
    zeros_left: u32,
}

impl CmdVelPolicy {
    /// Whether `twist` should go on the wire now.
    pub fn should_send(&mut self, twist: Twist) -> bool {
        if twist.linear != 0.0 || twist.angular != 0.0 {
            self.zeros_left = ZERO_REPEATS;
            true
        } else if self.zeros_left > 0 {
            self.zeros_left -= 1;
            true
        } else {
            false
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moving_sends_every_step_and_stopping_sends_a_few_zeros_then_nothing() {
        let mut p = CmdVelPolicy::default();
        assert!(!p.should_send(Twist::ZERO), "an idle start sends nothing");
        let go = Twist {
            linear: 0.1,
            angular: 0.0,
        };
        assert!(p.should_send(go) && p.should_send(go));
        let zeros: Vec<bool> = (0..6).map(|_| p.should_send(Twist::ZERO)).collect();
        assert_eq!(zeros, [true, true, true, false, false, false]);
    }
}
