//! Gripper mode: the arm's tool jogged by held keys in Cartesian space (forward and back
//! along the arm, round the base joint, up and down, pitch), named poses, and the joint
//! targets sent to the robot. As with driving, a key counts as held until the deadman
//! timeout after its last press, and the tool stops when the keys stop. A jog that would
//! leave what the arm can reach, or make a joint jump, stops at the edge with one log
//! line instead.

use super::Pilot;
use super::mode::Mode;
use navdeck_core::arm::{ArmConfig, Joints, Target, forward, inverse, move_time};
use navdeck_core::data::{ArmTarget, Level};

/// The tool's jog speed at start and its bounds, m/s; turns go at `TURN_PER_METRE` rad
/// per metre of that (navdeck's choice: 5 cm/s and 0.5 rad/s at start).
const JOG_SPEED: f64 = 0.05;
const JOG_SPEED_BOUNDS: (f64, f64) = (0.005, 0.3);
const TURN_PER_METRE: f64 = 10.0;
/// A jog step may turn no joint further than its speed limit allows in this many control
/// periods: more would be the jump of a solution on another branch.
const JUMP_PERIODS: f64 = 3.0;

/// What a held arm key moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArmAxis {
    /// Along the arm, away from the base (+) or towards it (-).
    Reach,
    /// Round the base joint, left (+) or right (-).
    Turn,
    /// Up (+) or down (-).
    Lift,
    /// Tool pitch, up (+) or down (-).
    Pitch,
}

/// A named pose of `[arm] poses`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArmPose {
    Home,
    Ready,
    Stow,
}

impl ArmPose {
    pub fn name(self) -> &'static str {
        match self {
            ArmPose::Home => "home",
            ArmPose::Ready => "ready",
            ArmPose::Stow => "stow",
        }
    }
}

/// The arm as the pilot keeps it.
#[derive(Clone, Debug)]
pub struct ArmPilot {
    pub config: ArmConfig,
    /// The joints asked for, and those the robot last reported.
    pub target: Joints,
    pub measured: Option<Joints>,
    /// Held keys: axis, direction (+1 or -1) and when last pressed.
    held: Vec<(ArmAxis, f64, f64)>,
    /// Tool speed, m/s.
    pub speed: f64,
    /// A target not yet sent, and how long its move should take.
    pending: Option<f64>,
    last_jog: Option<f64>,
    /// Why the last jog stopped at the edge, while the keys keep pushing there.
    pub at_edge: Option<String>,
}

impl ArmPilot {
    pub fn new(config: ArmConfig) -> Self {
        let target = config.pose("home").unwrap_or_default();
        Self {
            config,
            target,
            measured: None,
            held: Vec::new(),
            speed: JOG_SPEED,
            pending: None,
            last_jog: None,
            at_edge: None,
        }
    }

    /// The arm to `to` at its joints' speed limits (the mission's moves).
    /// Returns how long the move takes, seconds.
    pub fn move_to(&mut self, to: Joints) -> f64 {
        let within = move_time(&self.config, &self.joints(), &to);
        self.target = to;
        self.held.clear();
        self.pending = Some(within);
        self.at_edge = None;
        within
    }

    /// The joints the arm is at as far as navdeck knows: reported, else asked for.
    pub fn joints(&self) -> Joints {
        self.measured.unwrap_or(self.target)
    }

    /// Stops the arm where it is: keys let go, and the target brought back to the joints
    /// the robot last reported.
    pub fn halt(&mut self) {
        self.held.clear();
        self.last_jog = None;
        if let Some(m) = self.measured
            && m != self.target
        {
            self.target = m;
            self.pending = Some(0.0);
        }
    }

    /// The held keys' direction per axis at `t`, dropping keys past the deadman.
    fn velocity(&mut self, t: f64, timeout: f64) -> [f64; 4] {
        self.held.retain(|&(_, _, at)| t - at < timeout);
        let mut v = [0.0; 4];
        for &(axis, sign, _) in &self.held {
            let k = axis as usize;
            v[k] = sign;
        }
        v
    }
}

impl Pilot {
    /// The arm, when the config has one.
    pub fn arm(&self) -> Option<&ArmPilot> {
        self.hand.arm.as_ref()
    }

    /// Stops the arm where it is (stop key, emergency stop, link in doubt).
    pub(super) fn halt_arm(&mut self) {
        if let Some(arm) = self.hand.arm.as_mut() {
            arm.halt();
        }
    }

    /// A held arm key, pressed or auto-repeated at `t`.
    pub(super) fn arm_key(&mut self, axis: ArmAxis, sign: f64) {
        let now = self.now;
        let Some(arm) = self.hand.arm.as_mut() else {
            self.log(Level::Warn, "no arm: add an [arm] section to the config");
            return;
        };
        arm.held.retain(|&(a, _, _)| a != axis);
        arm.held.push((axis, sign, now));
        if arm.last_jog.is_none() {
            arm.last_jog = Some(now);
        }
    }

    /// The arm to a named pose, its joints together at their speed limits.
    pub(super) fn arm_pose(&mut self, pose: ArmPose) {
        let Some(arm) = self.hand.arm.as_mut() else {
            self.log(Level::Warn, "no arm: add an [arm] section to the config");
            return;
        };
        let Some(to) = arm.config.pose(pose.name()) else {
            return;
        };
        let within = arm.move_to(to);
        self.log(
            Level::Info,
            format!("arm to {} ({within:.1} s)", pose.name()),
        );
    }

    /// Jog speed up or down by 10 %, within bounds.
    pub(super) fn arm_speed(&mut self, faster: bool) {
        let Some(arm) = self.hand.arm.as_mut() else {
            return;
        };
        let factor = if faster { 1.1 } else { 1.0 / 1.1 };
        let (lo, hi) = JOG_SPEED_BOUNDS;
        arm.speed = (arm.speed * factor).clamp(lo, hi);
        let text = format!("arm jog {:.1} cm/s", arm.speed * 100.0);
        self.log(Level::Info, text);
    }

    /// Folds in the joints the robot reported.
    pub(super) fn arm_measured(&mut self, joints: [f64; 4]) {
        if let Some(arm) = self.hand.arm.as_mut()
            && joints.iter().all(|j| j.is_finite())
        {
            arm.measured = Some(Joints(joints));
        }
    }

    /// The arm's part of the command at `t`: a jog step while keys are held in gripper
    /// mode, or a pose asked for.
    pub(super) fn arm_command(&mut self, t: f64) -> Option<ArmTarget> {
        let timeout = self.settings.teleop.deadman_timeout;
        let period = self.settings.robot.control_period;
        let in_doubt = self.behaviours.gate.in_doubt();
        let gripper_mode = self.mode == Mode::Gripper && !in_doubt;
        let arm = self.hand.arm.as_mut()?;
        if in_doubt {
            // Control is lost or the robot e-stopped: the arm holds where it is.
            arm.halt();
        } else if !gripper_mode {
            arm.held.clear();
        }
        let v = arm.velocity(t, timeout);
        let dt = arm.last_jog.map_or(0.0, |at| (t - at).clamp(0.0, period));
        arm.last_jog = (v != [0.0; 4]).then_some(t);
        if v != [0.0; 4] && dt > 0.0 {
            let edge = jog(arm, v, dt, period);
            match edge {
                Ok(()) => {
                    arm.pending = Some(dt);
                    arm.at_edge = None;
                }
                Err(why) if arm.at_edge.as_deref() != Some(why.as_str()) => {
                    arm.at_edge = Some(why.clone());
                    self.log(Level::Warn, format!("arm stops at the edge: {why}"));
                }
                Err(_) => {}
            }
        }
        let arm = self.hand.arm.as_mut()?;
        arm.pending.take().map(|within| ArmTarget {
            joints: arm.target.0,
            within,
        })
    }
}

/// Moves the arm's target by the held keys' velocity `v` (per axis, ±1) over `dt`, or
/// says why it cannot.
fn jog(arm: &mut ArmPilot, v: [f64; 4], dt: f64, period: f64) -> Result<(), String> {
    let cfg = &arm.config;
    let tool = forward(cfg, &arm.target);
    let reach = tool.x.hypot(tool.y);
    let yaw = tool.y.atan2(tool.x);
    let (s, w) = (arm.speed, arm.speed * TURN_PER_METRE);
    let reach = reach + v[ArmAxis::Reach as usize] * s * dt;
    let yaw = yaw + v[ArmAxis::Turn as usize] * w * dt;
    let target = Target {
        x: reach * yaw.cos(),
        y: reach * yaw.sin(),
        z: tool.z + v[ArmAxis::Lift as usize] * s * dt,
        pitch: Some(tool.pitch - v[ArmAxis::Pitch as usize] * w * dt),
    };
    let solution = inverse(cfg, &target, &arm.target).map_err(|e| e.to_string())?;
    // Never a jump: no joint may turn further than its speed allows in a few periods.
    for k in 0..4 {
        let turn = (solution.joints.0[k] - arm.target.0[k]).abs();
        let most = cfg.limits.speed[k] * period * JUMP_PERIODS;
        if turn > most {
            return Err(format!(
                "joint {} would have to jump {:.0}° to follow",
                k + 1,
                turn.to_degrees()
            ));
        }
    }
    arm.target = solution.joints;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_forward_jog_moves_the_tool_along_the_arm_by_speed_times_time() {
        let mut arm = ArmPilot::new(ArmConfig::default());
        let before = forward(&arm.config, &arm.target);
        jog(&mut arm, [1.0, 0.0, 0.0, 0.0], 0.1, 0.1).unwrap();
        let after = forward(&arm.config, &arm.target);
        let moved = after.x.hypot(after.y) - before.x.hypot(before.y);
        assert!((moved - 0.005).abs() < 1e-6, "{moved}");
        assert!((after.z - before.z).abs() < 1e-6);
    }

    #[test]
    fn a_jog_out_of_reach_stops_at_the_edge_and_says_why() {
        let mut arm = ArmPilot::new(ArmConfig::default());
        let mut stopped = None;
        for _ in 0..400 {
            if let Err(why) = jog(&mut arm, [1.0, 0.0, 0.0, 0.0], 0.1, 0.1) {
                stopped = Some(why);
                break;
            }
        }
        let why = stopped.expect("the arm's reach ends");
        assert!(why.contains("reach") || why.contains("joint"), "{why}");
        let tool = forward(&arm.config, &arm.target);
        assert!(tool.x.hypot(tool.y) < 0.45, "{tool:?}");
    }
}
