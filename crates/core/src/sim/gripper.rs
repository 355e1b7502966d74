//! The gripper: jaws that take `actuation_time` to move, and the zone they catch blocks in.

use super::config::GripperConfig;
use crate::data::{GripperCommand, GripperState};
use crate::geometry::{Point2, Pose2};

#[derive(Clone, Debug)]
pub struct Gripper {
    /// Jaw position: 0 fully open, 1 fully closed.
    closure: f64,
    target: GripperCommand,
    /// Fraction of the full stroke travelled per second (infinite for instant jaws).
    speed: f64,
    reach_near: f64,
    reach_far: f64,
    half_width: f64,
    /// Index of the held block, and its pose in the robot frame.
    held: Option<(usize, Pose2)>,
}

impl Gripper {
    /// Jaws start closed on nothing.
    pub fn new(cfg: &GripperConfig) -> Self {
        let speed = if cfg.actuation_time > 0.0 {
            1.0 / cfg.actuation_time
        } else {
            f64::INFINITY
        };
        Self {
            closure: 1.0,
            target: GripperCommand::Close,
            speed,
            reach_near: cfg.reach_near,
            reach_far: cfg.reach_far,
            half_width: cfg.half_width,
            held: None,
        }
    }

    pub fn state(&self) -> GripperState {
        match (self.target, self.held) {
            (_, Some(_)) => GripperState::Holding,
            (GripperCommand::Close, None) if self.closure >= 1.0 => GripperState::Closed,
            (GripperCommand::Close, None) => GripperState::Closing,
            (GripperCommand::Open, None) if self.closure <= 0.0 => GripperState::Open,
            (GripperCommand::Open, None) => GripperState::Opening,
        }
    }

    /// Starts the jaws moving. Opening lets go of a held block at once, where it is.
    /// Returns true when the jaws have just finished closing (instant jaws) so the caller
    /// can look for a block to catch.
    pub fn command(&mut self, cmd: GripperCommand) -> bool {
        if cmd == self.target {
            return false;
        }
        self.target = cmd;
        if cmd == GripperCommand::Open {
            self.held = None;
        }
        self.advance(0.0)
    }

    /// Moves the jaws for `dt` seconds; true when closing finished during this call.
    pub fn advance(&mut self, dt: f64) -> bool {
        let stroke = if self.speed.is_finite() {
            self.speed * dt
        } else {
            1.0
        };
        match self.target {
            GripperCommand::Open => {
                self.closure = (self.closure - stroke).max(0.0);
                false
            }
            GripperCommand::Close if self.closure < 1.0 => {
                self.closure = (self.closure + stroke).min(1.0);
                self.closure >= 1.0
            }
            GripperCommand::Close => false,
        }
    }

    /// True while the jaws are not shut, so a block can slide into them.
    pub fn jaws_open(&self) -> bool {
        self.held.is_none() && self.closure < 1.0
    }

    /// How far a point in the jaw zone (`reach_near..reach_far` ahead of the robot centre,
    /// within `half_width` sideways) lies from the zone's middle; `None` outside it.
    pub fn jaw_offset(&self, robot: Pose2, p: Point2) -> Option<f64> {
        let l = robot.inverse_transform_point(p);
        let inside =
            l.x >= self.reach_near && l.x <= self.reach_far && l.y.abs() <= self.half_width;
        inside.then(|| (l.x - (self.reach_near + self.reach_far) / 2.0).hypot(l.y))
    }

    /// Catches block `index` whose pose is `block`, keeping it where it is relative to the robot.
    pub fn grab(&mut self, index: usize, robot: Pose2, block: Pose2) {
        let l = robot.inverse_transform_point(block.position());
        self.held = Some((index, Pose2::new(l.x, l.y, block.theta - robot.theta)));
    }

    /// How far ahead of the robot centre the jaws reach, metres.
    pub fn reach_far(&self) -> f64 {
        self.reach_far
    }

    pub fn held(&self) -> Option<usize> {
        self.held.map(|(i, _)| i)
    }

    /// Pose of the held block when the robot stands at `robot`.
    pub fn held_pose(&self, robot: Pose2) -> Option<(usize, Pose2)> {
        self.held.map(|(i, rel)| {
            let p = robot.transform_point(rel.position());
            (
                i,
                Pose2::new(
                    p.x,
                    p.y,
                    crate::geometry::wrap_angle(robot.theta + rel.theta),
                ),
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jaws_take_the_actuation_time() {
        let mut g = Gripper::new(&GripperConfig::default());
        assert_eq!(g.state(), GripperState::Closed);
        assert!(!g.command(GripperCommand::Open));
        assert_eq!(g.state(), GripperState::Opening);
        g.advance(0.6);
        assert_eq!(g.state(), GripperState::Opening);
        g.advance(0.4);
        assert_eq!(g.state(), GripperState::Open);
        g.command(GripperCommand::Close);
        assert!(!g.advance(0.99));
        assert_eq!(g.state(), GripperState::Closing);
        assert!(g.advance(0.02), "closing finishes after one second");
        assert_eq!(g.state(), GripperState::Closed);
    }

    #[test]
    fn jaw_zone_is_ahead_of_the_robot() {
        let g = Gripper::new(&GripperConfig::default());
        let robot = Pose2::new(1.0, 0.0, std::f64::consts::FRAC_PI_2);
        assert!(g.jaw_offset(robot, Point2::new(1.0, 0.1)).is_some());
        assert!(
            g.jaw_offset(robot, Point2::new(1.0, -0.1)).is_none(),
            "behind"
        );
        assert!(
            g.jaw_offset(robot, Point2::new(1.05, 0.1)).is_none(),
            "too far sideways"
        );
        assert!(
            g.jaw_offset(robot, Point2::new(1.0, 0.2)).is_none(),
            "beyond reach"
        );
    }
}
