//! A scripted stand-in for the console around the mission: straight-line paths, a gripper
//! that catches what lies between its jaws, hand-made landmark maps. No twin, no clock.

use navdeck::arm::{ArmConfig, Joints, forward};
use navdeck::data::{GripperCommand, GripperState};
use navdeck::geometry::{Point2, Pose2, wrap_angle};
use navdeck::map::costmap::{Costmap, FREE, NO_INFORMATION};
use navdeck::mission::step::{Inputs, Motion, Outputs, PathStatus};
use navdeck::mission::{Mission, MissionConfig};
use std::collections::BTreeMap;

pub const DT: f64 = 0.1;

/// A scripted console around the mission.
pub struct Rig {
    pub mission: Mission,
    pub t: f64,
    pub pose: Pose2,
    pub landmarks: BTreeMap<u32, Point2>,
    pub seen: Vec<u32>,
    pub camera_frame: bool,
    pub gripper: Option<GripperState>,
    pub path: PathStatus,
    pub map: Costmap,
    /// The cells of `map` a lidar found occupied (empty: no lidar).
    pub occupied: Vec<bool>,
    /// Scan the blocks' near faces each step (a lidar outlining them), else no scan.
    pub lidar: bool,
    /// The filter's position standard deviation the mission is told, metres.
    pub position_std: f64,
    /// Follow planned paths in straight lines at 0.2 m/s and run the gripper.
    pub auto: bool,
    /// Block centres by odd marker (where they really are), for the gripper.
    pub blocks: Vec<(u32, Point2)>,
    pub goal: Option<Point2>,
    /// Gripper command in progress and when it was given.
    pub pending: Option<(GripperCommand, f64)>,
    pub log: Vec<String>,
    pub commands: Vec<GripperCommand>,
    pub plans: Vec<(f64, Point2, String)>,
    /// An arm whose joints reach each target at once, and the targets asked for.
    pub arm: Option<(ArmConfig, [f64; 4])>,
    pub arm_moves: Vec<[f64; 4]>,
}

impl Rig {
    pub fn new(config: MissionConfig, map: Costmap) -> Self {
        Self {
            mission: Mission::new(config, 0.0),
            t: 0.0,
            pose: Pose2::new(0.0, 0.0, 0.0),
            landmarks: BTreeMap::new(),
            seen: vec![1],
            camera_frame: true,
            gripper: Some(GripperState::Closed),
            path: PathStatus::Idle,
            map,
            occupied: Vec::new(),
            lidar: false,
            position_std: 0.0,
            auto: true,
            blocks: Vec::new(),
            goal: None,
            pending: None,
            log: Vec::new(),
            commands: Vec::new(),
            plans: Vec::new(),
            arm: None,
            arm_moves: Vec::new(),
        }
    }

    /// The same rig with seed 000's default arm, at home, in the mission's hands.
    pub fn with_arm(mut self) -> Self {
        let config = ArmConfig::default();
        self.mission = self.mission.clone().with_arm(config.clone());
        let home = config.poses.home;
        self.arm = Some((config, home));
        self
    }

    /// Where the arm's tool tip is: world x, y and height above the floor.
    pub fn tool(&self) -> Option<[f64; 3]> {
        let (config, joints) = self.arm.as_ref()?;
        let t = forward(config, &Joints(*joints));
        let [x, y, z] = config.mount.to_robot([t.x, t.y, t.z]);
        let p = self.pose.transform_point(Point2::new(x, y));
        Some([p.x, p.y, z])
    }

    /// A 0.05 m block centred at (x, y), turned so both marked faces look towards -x.
    pub fn add_block(&mut self, odd: u32, x: f64, y: f64) {
        let k = 0.025 * std::f64::consts::FRAC_1_SQRT_2;
        self.landmarks.insert(odd, Point2::new(x - k, y + k));
        self.landmarks.insert(odd + 1, Point2::new(x - k, y - k));
        self.blocks.push((odd, Point2::new(x, y)));
        self.seen.extend([odd, odd + 1]);
    }

    /// The red gate centred at (-1, 1) on a wall along y, facing +x.
    pub fn add_red_gate(&mut self) {
        self.landmarks.insert(401, Point2::new(-1.0, 1.15));
        self.landmarks.insert(402, Point2::new(-1.0, 0.85));
    }

    /// The blocks' faces that look towards the robot, every 5 mm, in its frame: what a
    /// noiseless lidar with a 0.12 m least range returns from them.
    fn scan(&self) -> Vec<Point2> {
        let robot = self.pose.position();
        let mut hits = Vec::new();
        for &(_, c) in &self.blocks {
            for (nx, ny) in [(1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0)] {
                let face = Point2::new(c.x + 0.025 * nx, c.y + 0.025 * ny);
                if (robot.x - face.x) * nx + (robot.y - face.y) * ny <= 0.0 {
                    continue;
                }
                for k in -5..=5 {
                    let along = 0.005 * f64::from(k);
                    let p = Point2::new(face.x - along * ny, face.y + along * nx);
                    if p.distance(robot) >= 0.12 {
                        hits.push(self.pose.inverse_transform_point(p));
                    }
                }
            }
        }
        hits
    }

    pub fn step(&mut self) -> Outputs {
        let scan = if self.lidar { self.scan() } else { Vec::new() };
        let inputs = Inputs {
            t: self.t,
            pose: self.pose,
            landmarks: &self.landmarks,
            seen: if self.camera_frame { &self.seen } else { &[] },
            camera_frame: self.camera_frame,
            gripper: self.gripper,
            path: &self.path,
            map: &self.map,
            occupied: &self.occupied,
            scan: &scan,
            position_std: self.position_std,
            localized: false,
            arm: self.arm.as_ref().map(|a| a.1),
            can_pick: true,
        };
        let out = self.mission.step(&inputs);
        self.log.extend(out.log.iter().map(|(_, l)| l.clone()));
        if let Some(c) = out.gripper {
            self.commands.push(c);
            if self.auto {
                self.pending = Some((c, self.t));
                self.gripper = Some(match c {
                    GripperCommand::Open => GripperState::Opening,
                    GripperCommand::Close => GripperState::Closing,
                });
            }
        }
        if let (Some(j), Some(arm)) = (out.arm, self.arm.as_mut()) {
            arm.1 = j;
            self.arm_moves.push(j);
        }
        match &out.motion {
            Motion::Drive(tw) => {
                self.pose.theta = wrap_angle(self.pose.theta + tw.angular * DT);
                self.pose.x += tw.linear * DT * self.pose.theta.cos();
                self.pose.y += tw.linear * DT * self.pose.theta.sin();
            }
            Motion::PlanTo { goal, label } => {
                self.plans.push((self.t, *goal, label.clone()));
                if self.auto {
                    self.goal = Some(*goal);
                    let remaining = self.pose.position().distance(*goal);
                    self.path = PathStatus::Following { remaining };
                }
            }
            Motion::Follow if self.auto => self.follow(),
            _ => {}
        }
        if self.auto {
            self.run_gripper();
        }
        self.t += DT;
        out
    }

    fn follow(&mut self) {
        let Some(goal) = self.goal else { return };
        let d = self.pose.position().distance(goal);
        if d > 1e-9 {
            self.pose.theta = (goal.y - self.pose.y).atan2(goal.x - self.pose.x);
        }
        let step = d.min(0.2 * DT);
        self.pose.x += step * self.pose.theta.cos();
        self.pose.y += step * self.pose.theta.sin();
        let remaining = d - step;
        self.path = if remaining < 1e-9 {
            self.goal = None;
            PathStatus::Arrived
        } else {
            PathStatus::Following { remaining }
        };
    }

    /// The twin's jaws: a block 0.06-0.14 m ahead within 0.035 m sideways is caught.
    fn run_gripper(&mut self) {
        let Some((command, since)) = self.pending else {
            return;
        };
        if self.t - since < 0.5 {
            return;
        }
        self.pending = None;
        self.gripper = Some(match command {
            GripperCommand::Open => GripperState::Open,
            GripperCommand::Close => {
                let tool = self.tool();
                let caught = self.blocks.iter().any(|(_, c)| {
                    // An arm's jaws hold what is at its tool tip (the twin's tolerance).
                    if let Some([x, y, z]) = tool {
                        return c.distance(Point2::new(x, y)) <= 0.035 && (0.0..=0.06).contains(&z);
                    }
                    let local = self.pose.inverse_transform_point(*c);
                    (0.06..=0.14).contains(&local.x) && local.y.abs() <= 0.035
                });
                if caught {
                    GripperState::Holding
                } else {
                    GripperState::Closed
                }
            }
        });
    }

    /// Steps until `done` holds for the outputs; panics after `max` steps.
    pub fn until(&mut self, max: usize, done: impl Fn(&Outputs, &Rig) -> bool) -> Outputs {
        for _ in 0..max {
            let out = self.step();
            if done(&out, self) {
                return out;
            }
        }
        panic!(
            "not reached by t = {:.1}; state {}; log {:#?}",
            self.t,
            self.mission.state_label(),
            self.log
        );
    }

    pub fn logged(&self, text: &str) -> bool {
        self.log.iter().any(|l| l.contains(text))
    }
}

pub fn plan_to(out: &Outputs) -> Option<(Point2, &str)> {
    match &out.motion {
        Motion::PlanTo { goal, label } => Some((*goal, label.as_str())),
        _ => None,
    }
}

/// 4 m x 2 m: known free on the left half, unknown on the right (one long frontier at x = 0.95).
pub fn half_known() -> Costmap {
    let mut map = Costmap::new(40, 20, 0.1, Point2::new(-2.0, -1.0), NO_INFORMATION);
    for y in 0..20 {
        for x in 0..30 {
            map.set(x, y, FREE);
        }
    }
    map
}

pub fn all_free() -> Costmap {
    Costmap::new(40, 40, 0.1, Point2::new(-2.0, -2.0), FREE)
}

/// The mission's defaults, `total_blocks` blocks, and a camera that takes in the whole
/// rig map from anywhere: the tests that use it are about other things than coverage.
pub fn config(total_blocks: u32) -> MissionConfig {
    MissionConfig {
        total_blocks,
        ..all_seeing()
    }
}

/// The mission's defaults with a camera that sees the whole rig map at once.
pub fn all_seeing() -> MissionConfig {
    MissionConfig {
        view_range: 10.0,
        view_fov_deg: 360.0,
        ..MissionConfig::default()
    }
}
