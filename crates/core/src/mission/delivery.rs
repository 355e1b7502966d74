//! Delivering a held block (seed 001 section 8 "Delivery Sequence"): path to a point in
//! front of its gate, face the gate, creep in, open, back off. With an arm, the tool is
//! lowered to the floor before it opens, and raised again after.

use super::arm_moves::{ArmMove, ArmMoves, arrived};
use super::clearance::clear_ahead;
use super::config::{BACK_OFF_SPEED, MissionConfig};
use super::drive::{Wait, faces, opened, steer, turn_towards};
use super::leg::{Ctx, Leg, LegStep};
use super::objects::{Colour, Gate};
use super::pickup::name;
use super::step::{Inputs, Level, Motion};
use crate::data::GripperCommand;
use crate::geometry::{Point2, Twist, wrap_angle};

#[derive(Clone, Debug)]
enum Stage {
    Travel(Leg),
    Face,
    Forward,
    /// The arm puts the block on the floor below where it carries it.
    Lower(ArmMove),
    Open,
    /// The arm, empty, back to its carrying pose.
    Raise(ArmMove),
    BackOff,
}

/// What a delivery step comes to.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum DropEvent {
    Go(Motion, Option<GripperCommand>),
    /// Put down, its centre where it was let go.
    Delivered(Point2),
    GiveUp,
}

/// A delivery under way.
#[derive(Clone, Debug)]
pub(crate) struct Delivery {
    pub block: u32,
    pub colour: Colour,
    /// The drop place: the gate moved sideways to this delivery's slot.
    gate: Gate,
    /// How much further out than `drop_distance` this slot stops, metres.
    depth: f64,
    slot: usize,
    stage: Stage,
    since: f64,
    /// Where the block's centre was when the gripper opened.
    let_go: Option<Point2>,
}

/// Drop places side by side across the 0.3 m gate, then a row further out: a block lies
/// about 0.1 m ahead of the robot's centre, the body is 0.08 m round and a block lands a
/// few centimetres off its place, so 0.2 m apart keeps the next drop clear of the last.
const SLOT_OFFSETS: [f64; 2] = [-0.10, 0.10];
const ROW_DEPTH: f64 = 0.12;
/// How far ahead of the robot's centre a carried block's centre lies, metres.
const CARRIED_AHEAD: f64 = 0.10;
/// A gate estimate that moved or turned this much gets a new drop place (metres, radians).
const REFRESH_MOVE: f64 = 0.05;
const REFRESH_TURN: f64 = 20.0 * std::f64::consts::PI / 180.0;

/// The gate shifted along its width to `slot`'s place, and the extra depth of its row.
fn drop_place(gate: Gate, slot: usize) -> (Gate, f64) {
    let along = (-gate.normal.1, gate.normal.0);
    let offset = SLOT_OFFSETS[slot % SLOT_OFFSETS.len()];
    let depth = ROW_DEPTH * (slot / SLOT_OFFSETS.len()) as f64;
    let center = crate::geometry::Point2::new(
        gate.center.x + offset * along.0,
        gate.center.y + offset * along.1,
    );
    (Gate { center, ..gate }, depth)
}

impl Delivery {
    /// Delivers into drop place number `slot` of the gate: blocks already there are not
    /// pushed by the next one.
    pub fn new(
        block: u32,
        colour: Colour,
        gate: Gate,
        slot: usize,
        config: &MissionConfig,
        t: f64,
    ) -> Self {
        let (gate, depth) = drop_place(gate, slot);
        // Seed 001: drop_location = gate_center + offset * perpendicular.
        let goal = gate.in_front(config.drop_staging + depth);
        let label = format!("{} gate", colour.label());
        Self {
            block,
            colour,
            gate,
            depth,
            slot,
            stage: Stage::Travel(Leg::new(goal, label)),
            since: t,
            let_go: None,
        }
    }

    /// On the way, follows the gate as markers and map refine it: a drop place that
    /// moved more than 5 cm or turned more than 20° is planned to afresh (navdeck's).
    pub fn follow_gate(&mut self, gate: Gate, config: &MissionConfig) {
        if !matches!(self.stage, Stage::Travel(_)) {
            return;
        }
        let (place, depth) = drop_place(gate, self.slot);
        let (a, b) = (place.normal, self.gate.normal);
        let turned = a.0 * b.0 + a.1 * b.1 < REFRESH_TURN.cos();
        if turned || place.center.distance(self.gate.center) > REFRESH_MOVE {
            self.gate = place;
            self.depth = depth;
            let goal = place.in_front(config.drop_staging + depth);
            self.stage = Stage::Travel(Leg::new(goal, format!("{} gate", self.colour.label())));
        }
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
            Stage::Forward => format!("drive {block} into {gate} gate"),
            Stage::Lower(_) => format!("lower {block}"),
            Stage::Open => format!("drop {block}"),
            Stage::Raise(_) => "raise the arm".to_string(),
            Stage::BackOff => format!("back off from {gate} gate"),
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
        let error = wrap_angle(self.gate.facing() - pose.theta);
        let stop = DropEvent::Go(Motion::Stop, None);
        let joints = inputs.arm;
        let open = DropEvent::Go(Motion::Stop, Some(GripperCommand::Open));
        match &mut self.stage {
            Stage::Travel(leg) => match leg.step(inputs, config, ctx, log) {
                LegStep::Move(motion) => DropEvent::Go(motion, None),
                LegStep::Arrived => {
                    self.enter(Stage::Face, t);
                    stop
                }
                LegStep::GiveUp | LegStep::Unreachable(_) => DropEvent::GiveUp,
            },
            Stage::Face => {
                if faces(error) {
                    self.enter(Stage::Forward, t);
                    return stop;
                }
                DropEvent::Go(Motion::Drive(turn_towards(error, config)), None)
            }
            Stage::Forward => {
                let distance = pose.position().distance(self.gate.center);
                let creep = (config.drop_staging - config.drop_distance) / config.approach_speed;
                let stop_at = config.drop_distance + self.depth;
                // The wall (or a block delivered earlier) as the lidar mapped it stops the
                // creep too, wherever the markers put the gate.
                let blocked = clear_ahead(inputs.map, inputs.occupied, pose, stop_at).is_some();
                if distance <= stop_at || blocked || waited >= 2.0 * creep + 2.0 {
                    let lower = arm.map(|a| a.lower_to(config.block_size / 2.0, joints));
                    match lower {
                        Some(Ok(m)) => {
                            let block = name(self.colour, self.block);
                            log.push((Level::Info, format!("Lowering {block}")));
                            self.enter(Stage::Lower(m), t);
                        }
                        Some(Err(why)) => {
                            // Dropped from where it is carried rather than not at all.
                            log.push((Level::Warn, format!("The arm cannot lower: {why}")));
                            self.enter(Stage::Open, t);
                            return open;
                        }
                        None => {
                            self.enter(Stage::Open, t);
                            return open;
                        }
                    }
                    return stop;
                }
                let twist = Twist::new(config.approach_speed, steer(error));
                DropEvent::Go(Motion::Drive(twist), None)
            }
            Stage::Open => match opened(inputs.gripper, waited, config) {
                Wait::Waiting => stop,
                outcome => {
                    let ahead = Point2::new(pose.theta.cos(), pose.theta.sin());
                    self.let_go = Some(Point2::new(
                        pose.x + CARRIED_AHEAD * ahead.x,
                        pose.y + CARRIED_AHEAD * ahead.y,
                    ));
                    if outcome == Wait::TimedOut {
                        log.push((Level::Warn, "Gripper did not report open".into()));
                    }
                    if let Some(arm) = arm {
                        self.enter(Stage::Raise(arm.go_to_pose("home", joints)), t);
                        return stop;
                    }
                    self.enter(Stage::BackOff, t);
                    DropEvent::Go(Motion::Drive(Twist::new(-BACK_OFF_SPEED, 0.0)), None)
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
                DropEvent::Go(Motion::Drive(Twist::new(-BACK_OFF_SPEED, 0.0)), None)
            }
            Stage::BackOff => {
                if waited >= config.back_off_time - 1e-9 {
                    let here = pose.position();
                    return DropEvent::Delivered(self.let_go.unwrap_or(here));
                }
                DropEvent::Go(Motion::Drive(Twist::new(-BACK_OFF_SPEED, 0.0)), None)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Point2;

    fn gate(normal: (f64, f64)) -> Gate {
        Gate {
            colour: Colour::Red,
            markers: [401, 402],
            center: Point2::new(0.0, 2.0),
            normal,
        }
    }

    fn goal(d: &Delivery) -> Point2 {
        match &d.stage {
            Stage::Travel(leg) => leg.goal,
            _ => panic!("not travelling"),
        }
    }

    #[test]
    fn a_gate_that_turns_on_the_way_gets_a_new_drop_place_and_a_steady_one_does_not() {
        let config = MissionConfig::default();
        // First placed facing out of the arena (+y), then seen to face in (-y).
        let mut d = Delivery::new(421, Colour::Red, gate((0.0, 1.0)), 0, &config, 0.0);
        assert!(goal(&d).y > 2.0);
        d.follow_gate(gate((0.0, -1.0)), &config);
        let fixed = goal(&d);
        assert!(
            (fixed.y - (2.0 - config.drop_staging)).abs() < 1e-9,
            "{fixed:?}"
        );
        // A turn of 10° is inside the estimate's wobble: the plan stands.
        let (s, c) = (-100f64).to_radians().sin_cos();
        d.follow_gate(gate((c, s)), &config);
        assert_eq!(goal(&d), fixed);
    }
}
