//! Dead reckoning while the wheels are silent: the commands sent, run through the base's
//! speed and acceleration limits, stand in for the travel the odometry did not report.
//! A robot told to stop while turning fast still turns on while it brakes, and that
//! stretch belongs in the estimate as much as the commands before it.

use navdeck_core::data::WheelTravel;
use navdeck_core::data::robot::RobotConfig;
use navdeck_core::geometry::Twist;
use navdeck_core::slam::odometry::wheel_travel;

/// The integration step, seconds: the twin's physics step, fine enough that the ramps'
/// corners cost under a millimetre.
const STEP_S: f64 = 0.01;

/// The base's motion as reckoned from the commands since the wheels last reported.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Reckoning {
    /// When the silence began: the first command the wheels did not answer.
    pub since: f64,
    /// Everything reckoned since then.
    pub travel: WheelTravel,
    /// The base's twist as reckoned at `at`, and the command in force from then.
    velocity: Twist,
    at: f64,
    command: Twist,
}

impl Reckoning {
    /// Reckoning from `since`, with the base last measured moving at `velocity`.
    pub fn new(since: f64, velocity: Twist) -> Self {
        Self {
            since,
            travel: WheelTravel::default(),
            velocity,
            at: since,
            command: velocity,
        }
    }

    /// The command in force from now on.
    pub fn command(&mut self, next: Twist) {
        self.command = next;
    }

    /// Runs the command in force on to `t`; returns the wheel travel of that stretch.
    pub fn advance(&mut self, t: f64, robot: &RobotConfig) -> WheelTravel {
        let mut stretch = WheelTravel::default();
        let target = robot.clamp_twist(self.command);
        while self.at < t - 1e-9 {
            let h = STEP_S.min(t - self.at);
            if self.velocity == target && target.is_zero() {
                self.at = t;
                break;
            }
            let next_velocity = robot.ramp(self.velocity, target, h);
            // The speed changes linearly within the step: the mean twist gives its travel.
            let mean = self.velocity.halfway(next_velocity);
            let (left, right) = wheel_travel(mean, robot.track, h);
            stretch.left += left;
            stretch.right += right;
            self.velocity = next_velocity;
            self.at += h;
        }
        self.at = self.at.max(t);
        self.travel.left += stretch.left;
        self.travel.right += stretch.right;
        stretch
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn heading_change(travel: WheelTravel, robot: &RobotConfig) -> f64 {
        (travel.right - travel.left) / robot.track
    }

    #[test]
    fn a_stop_while_turning_brakes_through_the_turn_left() {
        let robot = RobotConfig::default();
        let spin = Twist::new(0.0, 2.5);
        let mut r = Reckoning::new(10.0, spin);
        // Turning at 2.5 rad/s for 0.3 s, then stopped: 0.75 rad, then w^2 / 2a more.
        r.advance(10.3, &robot);
        r.command(Twist::ZERO);
        let after_stop = heading_change(r.travel, &robot);
        assert!((after_stop - 0.75).abs() < 1e-6, "{after_stop}");
        r.advance(12.0, &robot);
        let braked = heading_change(r.travel, &robot) - after_stop;
        let expected = 2.5 * 2.5 / (2.0 * robot.max_angular_accel);
        assert!((braked - expected).abs() < 1e-3, "{braked} vs {expected}");
    }

    #[test]
    fn a_base_at_rest_with_no_command_reckons_nothing() {
        let robot = RobotConfig::default();
        let mut r = Reckoning::new(0.0, Twist::ZERO);
        assert_eq!(r.advance(30.0, &robot), WheelTravel::default());
    }

    #[test]
    fn a_command_from_rest_ramps_up_at_the_acceleration_limit() {
        let robot = RobotConfig::default();
        let mut r = Reckoning::new(0.0, Twist::ZERO);
        r.command(Twist::new(0.2, 0.0));
        let stretch = r.advance(1.0, &robot);
        // 0.2 s to reach 0.2 m/s at 1 m/s^2 covers 0.02 m, then 0.8 s at speed 0.16 m.
        let expected = 0.02 + 0.16;
        assert!((stretch.left - expected).abs() < 1e-9, "{stretch:?}");
        assert!((stretch.right - expected).abs() < 1e-9);
    }
}
