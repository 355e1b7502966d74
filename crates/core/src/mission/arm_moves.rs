//! The mission's arm (seed 000 section 6's pick: above the block, descend, close, lift):
//! where the tool should go for a block seen at a point on the floor, the joint targets
//! the mission asks for, and when a move has finished.

use crate::arm::{ArmConfig, Joints, Target, forward, inverse, move_time};
use crate::geometry::{Point2, Pose2};

/// The tool goes this far above the block before it descends, metres (navdeck's:
/// clear of a 5 cm block's top by its own height).
pub const ABOVE: f64 = 0.05;
/// A joint this close to its target has arrived, radians.
const ARRIVED: f64 = 0.02;
/// Longer than its move should take, a move counts as done anyway (navdeck's), seconds:
/// a robot that reports no joint states is given its move time and this.
const MOVE_SLACK: f64 = 0.5;
const MOVE_TIMEOUT: f64 = 3.0;

/// A joint move under way: where to, and how long it should take.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ArmMove {
    pub goal: Joints,
    pub within: f64,
}

/// The arm as the mission drives it.
#[derive(Clone, Debug)]
pub(crate) struct ArmMoves {
    pub config: ArmConfig,
    /// The joints last asked for.
    last: Joints,
    /// A target not yet handed to the console.
    out: Option<Joints>,
    /// The last `reach_from_centre`: its standoff and height, and its answer.
    reach: Option<((f64, f64), f64)>,
}

impl ArmMoves {
    pub fn new(config: ArmConfig) -> Self {
        let last = config.pose("home").unwrap_or_default();
        Self {
            config,
            last,
            out: None,
            reach: None,
        }
    }

    /// The target asked for since the last take, for the console to send.
    pub fn take(&mut self) -> Option<Joints> {
        self.out.take()
    }

    /// How far ahead of the robot's centre the block stands when the arm reaches for it:
    /// `standoff` ahead of the arm's base, or nearer, in 5 mm steps, until the tool reaches
    /// both the block's middle (`mid` above the floor) and `ABOVE` over it there (seed
    /// 002's locked wrist reaches less far than seed 000's free one).
    pub fn reach_from_centre(&mut self, standoff: f64, mid: f64) -> f64 {
        if let Some((asked, at)) = self.reach
            && asked == (standoff, mid)
        {
            return at;
        }
        let home = Joints(self.config.poses.home);
        let reaches = |x: f64| {
            [mid, mid + ABOVE]
                .iter()
                .all(|&z| self.solve([self.config.mount.x + x, 0.0, z], &home).is_ok())
        };
        let nearest = (0..=(standoff / 0.005) as usize)
            .map(|k| standoff - k as f64 * 0.005)
            .find(|&x| reaches(x))
            .unwrap_or(standoff);
        let at = self.config.mount.x + nearest;
        self.reach = Some(((standoff, mid), at));
        at
    }

    /// Starts a move to `goal` from where the arm is (`measured`, else the last target).
    fn start(&mut self, goal: Joints, measured: Option<[f64; 4]>) -> ArmMove {
        let from = measured.map_or(self.last, Joints);
        self.last = goal;
        self.out = Some(goal);
        ArmMove {
            goal,
            within: move_time(&self.config, &from, &goal),
        }
    }

    /// The tool to `height` metres above the floor over `block` (a world point seen from
    /// `pose`), or why it cannot reach.
    pub fn over(
        &mut self,
        block: Point2,
        height: f64,
        pose: Pose2,
        measured: Option<[f64; 4]>,
    ) -> Result<ArmMove, String> {
        let p = pose.inverse_transform_point(block);
        let current = measured.map_or(self.last, Joints);
        let joints = self.solve([p.x, p.y, height], &current)?;
        Ok(self.start(joints, measured))
    }

    /// Joints that put the tool at `point` in the robot's frame, nearest `current`.
    fn solve(&self, point: [f64; 3], current: &Joints) -> Result<Joints, String> {
        let a = self.config.mount.from_robot(point);
        inverse(&self.config, &Target::point(a[0], a[1], a[2]), current)
            .map(|s| s.joints)
            .map_err(|e| e.to_string())
    }

    /// The tool straight down to `height` from where the arm's target is now (placing a
    /// carried block where it would have dropped).
    pub fn lower_to(&mut self, height: f64, measured: Option<[f64; 4]>) -> Result<ArmMove, String> {
        let tool = forward(&self.config, &self.last);
        let floor = self.config.mount.to_robot([tool.x, tool.y, tool.z]);
        let current = measured.map_or(self.last, Joints);
        let joints = self.solve([floor[0], floor[1], height], &current)?;
        Ok(self.start(joints, measured))
    }

    /// The arm to its named pose `name` (home when the config lacks it).
    pub fn go_to_pose(&mut self, name: &str, measured: Option<[f64; 4]>) -> ArmMove {
        let home = Joints(self.config.poses.home);
        let goal = self.config.pose(name).unwrap_or(home);
        self.start(goal, measured)
    }
}

/// Whether a move `waited` seconds ago is over: the reported joints at the goal, or with
/// none reported its move time passed; after `MOVE_TIMEOUT` more it is over anyway.
pub(crate) fn arrived(m: &ArmMove, measured: Option<[f64; 4]>, waited: f64) -> bool {
    let at = |j: [f64; 4]| (0..4).all(|k| (j[k] - m.goal.0[k]).abs() < ARRIVED);
    match measured {
        Some(j) if at(j) => true,
        Some(_) => waited >= m.within + MOVE_TIMEOUT,
        None => waited >= m.within + MOVE_SLACK,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arm::forward;

    #[test]
    fn over_a_block_ahead_puts_the_tool_above_it_and_down_to_it() {
        let mut arm = ArmMoves::new(ArmConfig::default());
        let pose = Pose2::new(1.0, 2.0, std::f64::consts::FRAC_PI_2);
        // The block 0.14 m ahead of the robot (north) and 2 cm to its left (west).
        let block = Point2::new(0.98, 2.14);
        let m = arm.over(block, 0.025 + ABOVE, pose, None).unwrap();
        assert_eq!(arm.take(), Some(m.goal));
        assert_eq!(arm.take(), None, "handed out once");
        let t = forward(&arm.config, &m.goal);
        let r = arm.config.mount.to_robot([t.x, t.y, t.z]);
        assert!(
            (r[0] - 0.14).abs() < 1e-6 && (r[1] - 0.02).abs() < 1e-6,
            "{r:?}"
        );
        assert!((r[2] - 0.075).abs() < 1e-6, "{r:?}");
        assert!(m.within > 0.0);
        // Down by 5 cm, straight.
        let d = arm.lower_to(0.025, Some(m.goal.0)).unwrap();
        let t = forward(&arm.config, &d.goal);
        let r2 = arm.config.mount.to_robot([t.x, t.y, t.z]);
        assert!((r2[0] - r[0]).abs() < 1e-6 && (r2[1] - r[1]).abs() < 1e-6);
        assert!((r2[2] - 0.025).abs() < 1e-6);
    }

    #[test]
    fn the_locked_wrist_stops_the_robot_nearer_than_the_free_one() {
        let mut free = ArmMoves::new(ArmConfig::default());
        let at = free.reach_from_centre(0.25, 0.025);
        assert!((at - (free.config.mount.x + 0.25)).abs() < 1e-9, "{at}");
        let config = ArmConfig {
            solver: crate::arm::Solver::TwoDof,
            ..ArmConfig::default()
        };
        let mut locked = ArmMoves::new(config);
        let near = locked.reach_from_centre(0.25, 0.025);
        assert!(near < at, "{near} vs {at}");
        let p = Pose2::default();
        let block = Point2::new(near, 0.0);
        assert!(locked.over(block, 0.025, p, None).is_ok());
        assert!(locked.over(block, 0.025 + ABOVE, p, None).is_ok());
    }

    #[test]
    fn a_block_out_of_reach_says_why() {
        let mut arm = ArmMoves::new(ArmConfig::default());
        let far = arm.over(Point2::new(1.0, 0.0), 0.025, Pose2::default(), None);
        assert!(far.unwrap_err().contains("reach"));
        assert_eq!(arm.take(), None, "nothing asked for");
    }

    #[test]
    fn a_move_is_over_at_its_goal_or_after_its_time() {
        let m = ArmMove {
            goal: Joints([0.1, 0.2, 0.3, 0.4]),
            within: 1.0,
        };
        assert!(arrived(&m, Some([0.1, 0.2, 0.3, 0.41]), 0.1));
        assert!(!arrived(&m, Some([0.0, 0.2, 0.3, 0.4]), 3.9));
        assert!(arrived(&m, Some([0.0, 0.2, 0.3, 0.4]), 4.0));
        assert!(!arrived(&m, None, 1.4));
        assert!(arrived(&m, None, 1.5));
    }
}
