//! One planned leg: ask the console for a path once, follow it, and recover when there is
//! no path or no progress (seed 001 "Failure Modes & Recovery").

use super::config::{BACK_OFF_SPEED, MissionConfig, STUCK_PROGRESS};
use super::drive::Turn;
use super::step::{Inputs, Level, Motion, PathStatus};
use crate::geometry::{Point2, Twist};
use crate::map::costmap::is_lethal;

/// How far behind the robot the map must be clear for it to back up, metres.
const BACK_OFF_STEP: f64 = 0.05;

/// Counters and the plan-request clock shared by every leg of the mission.
#[derive(Clone, Debug, Default)]
pub(crate) struct Ctx {
    pub replans: usize,
    pub recoveries: usize,
    /// When the last `PlanTo` went out.
    pub last_plan: Option<f64>,
}

/// What a leg asks for this step.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum LegStep {
    Move(Motion),
    Arrived,
    /// Out of retries: hand over to manual.
    GiveUp,
    /// An exploration goal the planner cannot reach (the reason): the mission gives it up
    /// and tries the next one at once.
    Unreachable(String),
}

/// A path to one goal.
#[derive(Clone, Debug)]
pub(crate) struct Leg {
    pub goal: Point2,
    pub label: String,
    /// When this leg last asked for its path, if it is waiting for one.
    asked: Option<f64>,
    requests: u32,
    following: bool,
    /// Least remaining length seen, and when it last shrank by `STUCK_PROGRESS`.
    best: f64,
    best_t: f64,
    failures: u32,
    turn: Option<Turn>,
    /// When a back-up out of a stuck spot began, while it lasts.
    backing: Option<f64>,
    /// An exploration leg: its goal is one of many, so no path means the next one.
    replaceable: bool,
}

impl Leg {
    pub fn new(goal: Point2, label: String) -> Self {
        Self {
            goal,
            label,
            asked: None,
            requests: 0,
            following: false,
            best: f64::INFINITY,
            best_t: 0.0,
            failures: 0,
            turn: None,
            backing: None,
            replaceable: false,
        }
    }

    /// A leg to one exploration goal among many: with no path it reports `Unreachable`
    /// instead of turning and retrying the same goal.
    pub fn replaceable(goal: Point2, label: String) -> Self {
        Self {
            replaceable: true,
            ..Self::new(goal, label)
        }
    }

    /// Failed plans so far.
    pub fn failures(&self) -> u32 {
        self.failures
    }

    /// Failed plans so far and whether a retry turn is under way.
    pub fn retrying(&self) -> Option<u32> {
        self.turn.as_ref().map(|_| self.failures)
    }

    pub fn step(
        &mut self,
        inputs: &Inputs,
        config: &MissionConfig,
        ctx: &mut Ctx,
        log: &mut Vec<(Level, String)>,
    ) -> LegStep {
        let t = inputs.t;
        if let Some(turn) = &mut self.turn {
            if !turn.advance(inputs.pose, t) {
                return LegStep::Move(Motion::Drive(Twist::new(0.0, config.scan_speed)));
            }
            self.turn = None;
        }
        if let Some(since) = self.backing {
            if t - since < config.back_off_time && clear_behind(inputs) {
                return LegStep::Move(Motion::Drive(Twist::new(-BACK_OFF_SPEED, 0.0)));
            }
            self.backing = None;
            return self.ask(t, config, ctx, log);
        }
        let Some(asked) = self.asked else {
            return self.ask(t, config, ctx, log);
        };
        match inputs.path {
            PathStatus::Following { remaining } => {
                if !self.following {
                    self.following = true;
                    log.push((Level::Info, "Path found".into()));
                    log.push((Level::Info, format!("Following path to {}", self.label)));
                }
                if *remaining < self.best - STUCK_PROGRESS {
                    self.best = *remaining;
                    self.best_t = t;
                }
                // No progress for the timeout: replan (seed 001 section 7 "Path
                // Recalculation", 30 s), but back up first (navdeck's, after Nav2's BackUp
                // recovery; the robot may be pressed against what it cannot see).
                if t - self.best_t >= config.stuck_timeout {
                    if cooled(ctx, t, config) {
                        ctx.recoveries += 1;
                        log.push((
                            Level::Warn,
                            format!(
                                "Stuck: no progress for {:.0} s - backing up and replanning to {}",
                                config.stuck_timeout, self.label
                            ),
                        ));
                        self.backing = Some(t);
                        self.following = false;
                        return LegStep::Move(Motion::Drive(Twist::new(-BACK_OFF_SPEED, 0.0)));
                    }
                    return LegStep::Move(Motion::Stop);
                }
                LegStep::Move(Motion::Follow)
            }
            PathStatus::Arrived => LegStep::Arrived,
            PathStatus::NoPath(reason) if self.replaceable => LegStep::Unreachable(reason.clone()),
            PathStatus::NoPath(reason) => {
                self.failures += 1;
                self.asked = None;
                self.following = false;
                // Seed 001 "Path Planning Failure": turn a little and try again, then give up.
                if self.failures > config.no_path_retries {
                    log.push((
                        Level::Error,
                        format!(
                            "No path to {} after {} retries - switching to manual",
                            self.label, config.no_path_retries
                        ),
                    ));
                    return LegStep::GiveUp;
                }
                ctx.recoveries += 1;
                log.push((
                    Level::Warn,
                    format!(
                        "No path to {} ({reason}) - turning {:.0}° and retrying ({}/{})",
                        self.label, config.retry_turn_deg, self.failures, config.no_path_retries
                    ),
                ));
                let angle = config.retry_turn_deg.to_radians();
                self.turn = Some(Turn::new(inputs.pose, t, angle, config.scan_speed));
                LegStep::Move(Motion::Drive(Twist::new(0.0, config.scan_speed)))
            }
            // The path was dropped (or not taken up yet): ask again after the cooldown.
            PathStatus::Idle => {
                if t - asked >= config.replan_cooldown && cooled(ctx, t, config) {
                    return self.ask(t, config, ctx, log);
                }
                LegStep::Move(Motion::Stop)
            }
        }
    }

    fn ask(
        &mut self,
        t: f64,
        config: &MissionConfig,
        ctx: &mut Ctx,
        log: &mut Vec<(Level, String)>,
    ) -> LegStep {
        if !cooled(ctx, t, config) {
            return LegStep::Move(Motion::Stop);
        }
        if self.requests == 0 {
            log.push((Level::Info, format!("Thinking path to {}", self.label)));
        } else {
            ctx.replans += 1;
        }
        self.requests += 1;
        self.asked = Some(t);
        ctx.last_plan = Some(t);
        self.best = f64::INFINITY;
        self.best_t = t;
        LegStep::Move(Motion::PlanTo {
            goal: self.goal,
            label: self.label.clone(),
        })
    }
}

/// Whether the robot can back up: the planning map is not lethal a back-off step behind it.
fn clear_behind(inputs: &Inputs) -> bool {
    let pose = inputs.pose;
    let behind = Point2::new(
        pose.x - BACK_OFF_STEP * pose.theta.cos(),
        pose.y - BACK_OFF_STEP * pose.theta.sin(),
    );
    !is_lethal(inputs.map.at(behind))
}

/// Whether the replan cooldown since the last plan request is over.
fn cooled(ctx: &Ctx, t: f64, config: &MissionConfig) -> bool {
    ctx.last_plan
        .is_none_or(|last| t - last >= config.replan_cooldown - 1e-9)
}
