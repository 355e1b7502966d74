//! Delivering a held block (seed 001 section 8 "Delivery Sequence"): path to a point in
//! front of its gate, face the gate, creep in, open, back off. With an arm, the tool is
//! lowered to the floor before it opens, and raised again after.

use super::arm_moves::{ArmMove, ArmMoves, arrived};
use super::config::{BACK_OFF_SPEED, MissionConfig};
use super::drive::{Wait, faces, opened, turn_towards};
use super::drop_places::{in_lane_of, open, shifted, standable};
use super::leg::{Ctx, Leg, LegStep};
use super::objects::{Colour, Gate};
use super::pickup::name;
use super::step::{Inputs, Level, Motion};
use crate::data::GripperCommand;
use crate::geometry::{Point2, Twist, wrap_angle};
use crate::map::costmap::Costmap;

#[derive(Clone, Debug)]
enum Stage {
    Travel(Leg),
    Face,
    /// Creeping in; the nearest the robot has come to the drop place, and when.
    Forward(Progress),
    /// The arm puts the block on the floor below where it carries it.
    Lower(ArmMove),
    Open,
    /// The arm, empty, back to its carrying pose.
    Raise(ArmMove),
    BackOff,
    /// Backing away from a drop place where the creep stopped short of the gate's region,
    /// to try this other drop place instead, still holding the block.
    Withdraw(usize),
    /// Looking at where the block was let go: the lidar's map or the camera finds it there.
    Check,
}

/// What a delivery step comes to.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum DropEvent {
    Go(Motion, Option<GripperCommand>),
    /// Put down at its gate, its centre where it was let go, in drop place `slot`.
    Delivered {
        at: Point2,
        slot: usize,
    },
    /// Let go in drop place `slot`, but not at its gate, or not found where it was let
    /// go: the block is somewhere else, and not delivered (the reason).
    Missed {
        why: String,
        slot: usize,
        /// Where the block is, as near as the robot can tell.
        at: Point2,
    },
    GiveUp,
    /// No drop place left where the block would surely count: it stays held.
    Full,
}

/// A delivery under way.
#[derive(Clone, Debug)]
pub(crate) struct Delivery {
    pub block: u32,
    pub colour: Colour,
    /// The gate as last estimated.
    gate: Gate,
    /// The drop place: the gate moved sideways to this delivery's slot.
    place: Gate,
    /// How much further out than `drop_distance` this slot stops, metres.
    depth: f64,
    slot: usize,
    /// Drop places free at the gate, in the order to try them, and those tried so far.
    free: Vec<usize>,
    tried: Vec<usize>,
    /// Every free drop place had no path once: legs now turn and retry before giving up.
    every_place_tried: bool,
    /// The gate's estimated normal points behind its wall (no drop place on its side is
    /// mapped, those on the other side are): this delivery approaches from the other side.
    turned_round: bool,
    stage: Stage,
    since: f64,
    /// Where the block's centre was when the gripper opened.
    let_go: Option<Point2>,
}

/// A gate estimate that moved or turned this much gets a new drop place (metres, radians).
const REFRESH_MOVE: f64 = 0.05;
const REFRESH_TURN: f64 = 20.0 * std::f64::consts::PI / 180.0;
/// How long the robot looks for the block it let go, seconds: the planning map folds in a
/// scan of a still robot every 2 s (pilot mapping.rs SCAN_EVERY), and twenty camera frames.
const CHECK_TIME: f64 = 2.0;
/// An occupied cell this near the let-go point is the block, metres: its 0.035 m
/// half-diagonal and a centimetre cell either side.
const FOUND_NEAR: f64 = 0.055;

impl Delivery {
    /// Delivers into the first of the gate's `free` drop places (in order; one the map
    /// shows no place to stand for is passed over on the way): blocks already there are
    /// not pushed by the next one. `None` when the gate has no free drop place.
    pub fn new(
        block: u32,
        colour: Colour,
        gate: Gate,
        free: Vec<usize>,
        config: &MissionConfig,
        t: f64,
    ) -> Option<Self> {
        let first = *free.first()?;
        let mut d = Self {
            block,
            colour,
            gate,
            place: gate,
            depth: 0.0,
            slot: first,
            free,
            tried: Vec::new(),
            every_place_tried: false,
            turned_round: false,
            stage: Stage::Face,
            since: t,
            let_go: None,
        };
        d.travel_to(first, config);
        Some(d)
    }

    /// Whether the robot could stand at drop place `slot`'s staging point and stop on `map`.
    fn standable(&self, slot: usize, map: &Costmap, config: &MissionConfig) -> bool {
        let (staging, stop) = self.staging_and_stop(self.gate, slot, config);
        standable(map, staging, stop)
    }

    fn staging_and_stop(
        &self,
        gate: Gate,
        slot: usize,
        config: &MissionConfig,
    ) -> (Point2, Point2) {
        let (place, depth) = shifted(gate, slot);
        let staging = place.in_front(config.drop_staging + depth);
        (staging, place.in_front(config.drop_distance + depth))
    }

    /// The gate as this delivery approaches it: turned round when it was found to face
    /// behind its wall.
    fn oriented(&self, gate: Gate) -> Gate {
        match self.turned_round {
            true => Gate {
                normal: (-gate.normal.0, -gate.normal.1),
                ..gate
            },
            false => gate,
        }
    }

    /// When no free drop place on the gate's side is on mapped floor and one on the other
    /// side is, the gate's normal points behind its wall: the first such drop place on the
    /// other side.
    fn other_side(&self, map: &Costmap, config: &MissionConfig) -> Option<usize> {
        let on = |gate: Gate, slot: usize| {
            let (staging, stop) = self.staging_and_stop(gate, slot, config);
            open(map, staging, stop)
        };
        let turned = Gate {
            normal: (-self.gate.normal.0, -self.gate.normal.1),
            ..self.gate
        };
        let here = self.free.iter().any(|&s| on(self.gate, s));
        (!here).then(|| self.free.iter().copied().find(|&s| on(turned, s)))?
    }

    /// Whether a block in drop place `slot` would stand in the way of a creep into a free
    /// place nearer the wall: while the map settles, a place behind may look unusable for
    /// a moment, and filling the row in front first would lose it for good.
    fn in_lane_of_free(&self, slot: usize) -> bool {
        self.free.iter().any(|&behind| in_lane_of(slot, behind))
    }

    /// The first free drop place not tried yet that the robot could stand at, else the
    /// first not tried at all.
    fn next_slot(&self, map: &Costmap, config: &MissionConfig) -> Option<usize> {
        let untried: Vec<usize> = (self.free.iter().copied())
            .filter(|s| !self.tried.contains(s))
            .collect();
        (untried.iter().copied())
            .find(|&s| self.standable(s, map, config))
            .or(untried.first().copied())
    }

    /// Plans to drop place `slot`'s staging point: a leg that reports no path at once, so
    /// another drop place is tried instead of the same point again (until every one was).
    fn travel_to(&mut self, slot: usize, config: &MissionConfig) {
        let goal = self.aim_at(slot, config);
        self.tried.push(slot);
        let label = format!("{} gate", self.colour.label());
        self.stage = Stage::Travel(if self.every_place_tried {
            Leg::new(goal, label)
        } else {
            Leg::replaceable(goal, label)
        });
    }

    /// Makes drop place `slot` the one delivered to; its staging point, where the leg goes.
    fn aim_at(&mut self, slot: usize, config: &MissionConfig) -> Point2 {
        let (place, depth) = shifted(self.gate, slot);
        (self.slot, self.place, self.depth) = (slot, place, depth);
        // Seed 001: drop_location = gate_center + offset * perpendicular.
        place.in_front(config.drop_staging + depth)
    }

    /// After every free drop place had no path, each retry (turn, look, plan again) goes to
    /// the next free drop place in turn, never to the same point twice running.
    fn retry_elsewhere(&mut self, config: &MissionConfig, log: &mut Vec<(Level, String)>) {
        let at = self.free.iter().position(|&s| s == self.slot).unwrap_or(0);
        let Some(&next) = self.free.get((at + 1) % self.free.len().max(1)) else {
            return;
        };
        if next == self.slot {
            return;
        }
        let goal = self.aim_at(next, config);
        if let Stage::Travel(leg) = &mut self.stage {
            leg.goal = goal;
        }
        log.push((
            Level::Info,
            format!(
                "Next try: drop place {} of the {} gate",
                next + 1,
                self.colour.label()
            ),
        ));
    }

    /// On the way, follows the gate as markers and map refine it: a drop place that
    /// moved more than 5 cm or turned more than 20° is planned to afresh (navdeck's).
    /// Facing the gate and creeping in, the drop place follows the smaller refinements:
    /// the markers seen from close up place the gate best, its first sightings were
    /// centimetres off, and the creep steers onto the drop place's line as it is now. A
    /// larger jump is not driven sideways into: the block is let go and checked.
    pub fn follow_gate(&mut self, gate: Gate, config: &MissionConfig) {
        let gate = self.oriented(gate);
        let (place, depth) = shifted(gate, self.slot);
        let (a, b) = (place.normal, self.place.normal);
        let turned = a.0 * b.0 + a.1 * b.1 < REFRESH_TURN.cos();
        let moved = turned || place.center.distance(self.place.center) > REFRESH_MOVE;
        if matches!(self.stage, Stage::Face | Stage::Forward(_)) && !moved {
            (self.place, self.depth) = (place, depth);
        }
        if !matches!(self.stage, Stage::Travel(_)) {
            self.gate = gate;
            return;
        }
        self.gate = gate;
        if moved {
            self.tried.retain(|&s| s != self.slot);
            self.travel_to(self.slot, config);
        }
    }

    /// Whether the arm is at work putting the block down.
    pub fn arm_engaged(&self) -> bool {
        matches!(self.stage, Stage::Lower(_) | Stage::Raise(_))
    }

    pub fn label(&self) -> String {
        let block = name(self.colour, self.block);
        let gate = self.colour.label();
        match &self.stage {
            Stage::Travel(leg) if leg.retrying().is_some() => {
                format!("no path: retry deliver {block} to {gate} gate")
            }
            Stage::Travel(_) => format!("deliver {block} to {gate} gate"),
            Stage::Face => format!("face {gate} gate with {block}"),
            Stage::Forward(_) => format!("drive {block} into {gate} gate"),
            Stage::Lower(_) => format!("lower {block}"),
            Stage::Open => format!("drop {block}"),
            Stage::Raise(_) => "raise the arm".to_string(),
            Stage::BackOff => format!("back off from {gate} gate"),
            Stage::Withdraw(_) => format!("back off from {gate} gate with {block}"),
            Stage::Check => format!("look for {block} at {gate} gate"),
        }
    }

    fn enter(&mut self, stage: Stage, t: f64) {
        self.stage = stage;
        self.since = t;
    }

    pub fn step(
        &mut self,
        inputs: &Inputs,
        config: &MissionConfig,
        ctx: &mut Ctx,
        arm: Option<&mut ArmMoves>,
        log: &mut Vec<(Level, String)>,
    ) -> DropEvent {
        let (t, pose) = (inputs.t, inputs.pose);
        let waited = t - self.since;
        let error = wrap_angle(self.place.facing() - pose.theta);
        let (stop, open, back_off) = (stopped(), opening(), backing_off());
        let joints = inputs.arm;
        if matches!(self.stage, Stage::Travel(_))
            && let Some(slot) = self.other_side(inputs.map, config)
        {
            log.push((
                Level::Warn,
                format!(
                    "The drop places of the {} gate lie behind its wall on the map - approaching it from the other side",
                    self.colour.label()
                ),
            ));
            self.turned_round = !self.turned_round;
            self.gate.normal = (-self.gate.normal.0, -self.gate.normal.1);
            self.tried.clear();
            self.travel_to(slot, config);
        }
        let map = inputs.map;
        if matches!(self.stage, Stage::Travel(_))
            && !self.standable(self.slot, map, config)
            && let Some(next) = (self.next_slot(map, config))
                .filter(|&s| self.standable(s, map, config) && !self.in_lane_of_free(s))
        {
            log.push((
                Level::Warn,
                format!(
                    "Drop place {} of the {} gate lies in a wall or ring on the map - trying drop place {}",
                    self.slot + 1,
                    self.colour.label(),
                    next + 1
                ),
            ));
            self.travel_to(next, config);
        }
        let failures = match &self.stage {
            Stage::Travel(leg) => leg.failures(),
            _ => 0,
        };
        match &mut self.stage {
            Stage::Travel(leg) => match leg.step(inputs, config, ctx, log) {
                LegStep::Move(motion) => {
                    if leg.failures() > failures {
                        self.retry_elsewhere(config, log);
                    }
                    DropEvent::Go(motion, None)
                }
                LegStep::Arrived => {
                    self.enter(Stage::Face, t);
                    stop
                }
                LegStep::Unreachable(reason) => {
                    let (gate, slot) = (self.colour.label(), self.slot + 1);
                    if let Some(next) = self.next_slot(inputs.map, config) {
                        log.push((
                            Level::Warn,
                            format!(
                                "No path to drop place {slot} of the {gate} gate ({reason}) - trying drop place {}",
                                next + 1
                            ),
                        ));
                        self.travel_to(next, config);
                        return stop;
                    }
                    // Every free drop place tried: seed 001's recovery (turn, look, plan
                    // again) to the first, which gives up after its retries.
                    log.push((
                        Level::Warn,
                        format!(
                            "No path to any of the {} drop places free at the {gate} gate ({reason}) - turning and retrying",
                            self.tried.len()
                        ),
                    ));
                    self.tried.clear();
                    self.every_place_tried = true;
                    let first = self.next_slot(inputs.map, config).unwrap_or(self.slot);
                    self.travel_to(first, config);
                    stop
                }
                LegStep::GiveUp => DropEvent::GiveUp,
            },
            Stage::Face => {
                if faces(error) {
                    self.enter(Stage::Forward(Progress::new(t)), t);
                    return stop;
                }
                DropEvent::Go(Motion::Drive(turn_towards(error, config)), None)
            }
            Stage::Forward(_) => self.creep(inputs, config, arm, log),
            Stage::Open => match opened(inputs.gripper, waited, config) {
                Wait::Waiting => stop,
                outcome => {
                    self.let_go = Some(carried_at(pose));
                    if outcome == Wait::TimedOut {
                        log.push((Level::Warn, "Gripper did not report open".into()));
                    }
                    if let Some(arm) = arm {
                        self.enter(Stage::Raise(arm.go_to_pose("home", joints)), t);
                        return stop;
                    }
                    self.enter(Stage::BackOff, t);
                    back_off
                }
            },
            Stage::Lower(m) => {
                if !arrived(m, joints, waited) {
                    return stop;
                }
                self.enter(Stage::Open, t);
                open
            }
            Stage::Raise(m) => {
                if !arrived(m, joints, waited) {
                    return stop;
                }
                self.enter(Stage::BackOff, t);
                back_off
            }
            Stage::BackOff => {
                if waited >= config.back_off_time - 1e-9 {
                    self.enter(Stage::Check, t);
                    return stop;
                }
                back_off
            }
            Stage::Withdraw(next) => {
                if waited >= config.back_off_time - 1e-9 {
                    let next = *next;
                    self.travel_to(next, config);
                    return stop;
                }
                back_off
            }
            Stage::Check => self.check(inputs, waited),
        }
    }
}

/// Standing still, opening the gripper there, backing straight away.
fn stopped() -> DropEvent {
    DropEvent::Go(Motion::Stop, None)
}

fn opening() -> DropEvent {
    DropEvent::Go(Motion::Stop, Some(GripperCommand::Open))
}

fn backing_off() -> DropEvent {
    DropEvent::Go(Motion::Drive(Twist::new(-BACK_OFF_SPEED, 0.0)), None)
}

mod check;
mod creep;
use creep::{Progress, carried_at};
#[cfg(test)]
mod tests;
