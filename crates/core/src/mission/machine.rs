//! The mission state machine (seed 001 sections 7-8): scan, choose, explore, pick up,
//! deliver, recover. Driven only by `Inputs`; every time it keeps came in through them.

use super::arm_moves::ArmMoves;
use super::config::{LOST_SCAN_AFTER, MissionConfig, RELOCATE_STANDOFF};
use super::delivery::{Delivery, DropEvent};
use super::drive::Turn;
use super::drop_places::DROP_PLACES;
use super::explored::{Explored, GivenUp, Unexplained};
use super::leg::{Ctx, Leg, LegStep};
use super::objects::{Colour, Objects};
use super::phase::{Cause, Phase};
use super::pickup::{PickEvent, name};
use super::step::{Inputs, Level, Motion, Outputs};
use crate::data::GripperCommand;
use crate::geometry::Twist;
use crate::perception::markers::MarkerCategory;
use std::collections::{BTreeMap, BTreeSet};

pub use super::resume::Resumed;

/// One block's story: odd marker, found, picked up, delivered (session times).
pub type TimelineEntry = (u32, f64, Option<f64>, Option<f64>);

/// The autonomous mission.
#[derive(Clone, Debug)]
pub struct Mission {
    pub(super) config: MissionConfig,
    pub(super) objects: Objects,
    pub(super) phase: Phase,
    pub(super) ctx: Ctx,
    /// Last time a camera frame showed any marker.
    pub(super) last_marker: f64,
    pub(super) explored: Explored,
    pub(super) given_up: GivenUp,
    /// Why the mission handed over to manual, once it has.
    pub(super) handover: Option<&'static str>,
    /// Demoted blocks and when; attempts per block.
    pub(super) demoted: BTreeMap<u32, f64>,
    pub(super) attempts: BTreeMap<u32, u32>,
    pub(super) announced: BTreeSet<Colour>,
    pub(super) timeline: Vec<TimelineEntry>,
    pub(super) held: Option<u32>,
    /// Markers of delivered blocks: ignored by the filter forever.
    pub(super) delivered_markers: Vec<u32>,
    /// The drop places taken at each colour's gate (drop_places.rs).
    pub(super) drop_slots: BTreeMap<Colour, BTreeSet<usize>>,
    /// Lost, the robot already went back to a landmark and scanned there.
    pub(super) relocated: bool,
    /// The arm that picks and places blocks, when the robot has one.
    pub(super) arm: Option<ArmMoves>,
    /// What a fleet's other robots claim and explored (`shared.rs`).
    pub(super) shared: super::shared::Shared,
}

pub(super) enum Tick {
    Out(Motion, Option<GripperCommand>),
    Again,
}

impl Mission {
    /// A mission starting at session time `t` (the lost-robot clock starts then).
    pub fn new(config: MissionConfig, t: f64) -> Self {
        Self {
            config,
            objects: Objects::default(),
            phase: Phase::Start,
            ctx: Ctx::default(),
            last_marker: t,
            explored: Explored::default(),
            given_up: GivenUp::default(),
            handover: None,
            demoted: BTreeMap::new(),
            attempts: BTreeMap::new(),
            announced: BTreeSet::new(),
            timeline: Vec::new(),
            held: None,
            delivered_markers: Vec::new(),
            shared: Default::default(),
            drop_slots: BTreeMap::new(),
            relocated: false,
            arm: None,
        }
    }

    /// The same mission picking with `arm` (seed 000's pick) instead of driving into
    /// blocks.
    pub fn with_arm(mut self, arm: crate::arm::ArmConfig) -> Self {
        self.arm = Some(ArmMoves::new(arm));
        self
    }

    /// One control step. Once the mission hands over, every later step says `to_manual`
    /// and stops; once done, it stops.
    pub fn step(&mut self, inputs: &Inputs) -> Outputs {
        let mut log = Vec::new();
        if (inputs.camera_frame && !inputs.seen.is_empty()) || inputs.localized {
            self.last_marker = inputs.t;
        }
        self.note_found(inputs, &mut log);
        self.shared.home.get_or_insert(inputs.pose.position());
        let fov = self.config.view_fov_deg.to_radians();
        (self.explored.coverage).look(inputs.map, inputs.pose, self.config.view_range, fov);
        let mut out = Outputs::new(Motion::Stop);
        for _ in 0..4 {
            if let Tick::Out(motion, gripper) = self.tick(inputs, &mut log) {
                out.motion = motion;
                out.gripper = gripper;
                break;
            }
        }
        out.arm = self.arm.as_mut().and_then(ArmMoves::take).map(|j| j.0);
        out.log = log;
        out.to_manual = matches!(self.phase, Phase::Manual);
        out.ignore_markers = self.ignored();
        out
    }

    fn tick(&mut self, inputs: &Inputs, log: &mut Vec<(Level, String)>) -> Tick {
        let t = inputs.t;
        let scan = Motion::Drive(Twist::new(0.0, self.config.scan_speed));
        let exploring = matches!(
            self.phase,
            Phase::Explore { .. } | Phase::Scan { initial: false, .. }
        );
        // A block to pick up interrupts exploring, while the arm (if any) answers.
        if exploring && inputs.can_pick && self.deliverable(inputs.pose.position()).is_some() {
            self.phase = Phase::Choose;
            return Tick::Again;
        }
        // No marker for 10 s while exploring, and the filter no longer sure of the position
        // (navdeck's trigger): rotate to scan, as seed 001 "Robot Lost" says. Crossing open
        // space on odometry alone is not being lost.
        let unsure = inputs.position_std > self.config.lost_position_std;
        if exploring && t - self.last_marker >= LOST_SCAN_AFTER && unsure {
            self.ctx.recoveries += 1;
            log.push((
                Level::Warn,
                format!("No landmarks for {LOST_SCAN_AFTER:.0} s - rotating to scan"),
            ));
            self.phase = Phase::Lost(t, None);
        }
        match &mut self.phase {
            Phase::Start => {
                // One full turn in place first (seed 001 section 7 rotates for 30 s instead).
                log.push((Level::Info, "Initial rotation scan".into()));
                self.phase = Phase::Scan {
                    turn: Turn::full(inputs.pose, t, self.config.scan_speed),
                    initial: true,
                };
                Tick::Out(scan, None)
            }
            Phase::Scan { turn, .. } => {
                if turn.advance(inputs.pose, t) {
                    self.phase = Phase::Choose;
                    return Tick::Again;
                }
                Tick::Out(scan, None)
            }
            Phase::Choose => {
                self.choose(inputs, log);
                Tick::Again
            }
            Phase::Explore { leg, target } => {
                match leg.step(inputs, &self.config, &mut self.ctx, log) {
                    LegStep::Move(motion) => Tick::Out(motion, None),
                    LegStep::Arrived => {
                        let (goal, target) = (leg.goal, target.clone());
                        self.arrived(goal, target);
                        log.push((Level::Info, "Arrived - scanning".into()));
                        self.phase = Phase::Scan {
                            turn: Turn::full(inputs.pose, t, self.config.scan_speed),
                            initial: false,
                        };
                        Tick::Out(scan, None)
                    }
                    LegStep::Unreachable(reason) => {
                        let (goal, target, label) = (leg.goal, target.clone(), leg.label.clone());
                        self.give_up(goal, &target);
                        log.push((
                            Level::Warn,
                            format!(
                                "No path to {label} ({reason}) - giving it up for the next target"
                            ),
                        ));
                        self.phase = Phase::Choose;
                        Tick::Again
                    }
                    LegStep::GiveUp => self.manual(Cause::Unreachable),
                }
            }
            Phase::Lost(since, relocating) => {
                if t - self.last_marker < LOST_SCAN_AFTER {
                    log.push((Level::Success, "Landmarks back in view".into()));
                    self.relocated = false;
                    self.phase = Phase::Choose;
                    return Tick::Again;
                }
                if let Some(leg) = relocating {
                    return match leg.step(inputs, &self.config, &mut self.ctx, log) {
                        LegStep::Move(motion) => Tick::Out(motion, None),
                        // There: scan again, facing every way, before giving up.
                        LegStep::Arrived => {
                            self.relocated = true;
                            self.phase = Phase::Lost(t, None);
                            Tick::Out(scan, None)
                        }
                        _ => {
                            let label = leg.label.clone();
                            log.push((
                                Level::Error,
                                format!(
                                    "Robot lost: no landmarks in view even at {label} - switching to manual"
                                ),
                            ));
                            self.manual(Cause::Lost)
                        }
                    };
                }
                let scanned = t - *since;
                if t - self.last_marker >= self.config.lost_timeout
                    && scanned >= self.config.lost_timeout - LOST_SCAN_AFTER
                {
                    if self.relocated {
                        log.push((
                            Level::Error,
                            "Robot lost: no landmarks in view even after going back and scanning - switching to manual".into(),
                        ));
                        return self.manual(Cause::Lost);
                    }
                    let robot = inputs.pose.position();
                    // A block's marker moves with it and faces any way: go back to a fixed one.
                    let fixed = (inputs.landmarks.iter()).filter(|&(&id, _)| {
                        !matches!(
                            MarkerCategory::of(id),
                            MarkerCategory::RedBlock | MarkerCategory::BlueBlock
                        )
                    });
                    let nearest =
                        fixed.min_by(|a, b| a.1.distance(robot).total_cmp(&b.1.distance(robot)));
                    let Some((&id, &at)) = nearest else {
                        log.push((
                            Level::Error,
                            format!(
                                "Robot lost: no landmarks for {:.0} s - switching to manual",
                                self.config.lost_timeout
                            ),
                        ));
                        return self.manual(Cause::Lost);
                    };
                    // Odometry still holds the pose roughly: go where landmarks were seen.
                    let goal = super::drive::towards(at, robot, RELOCATE_STANDOFF);
                    let label = format!("marker {id}");
                    log.push((
                        Level::Warn,
                        format!(
                            "No landmarks for {:.0} s - going back to {label}, the nearest seen",
                            self.config.lost_timeout
                        ),
                    ));
                    *relocating = Some(Leg::new(goal, label));
                    return Tick::Again;
                }
                Tick::Out(scan, None)
            }
            Phase::Pickup(pickup) if !inputs.can_pick && !pickup.arm_engaged() => {
                let block = name(pickup.colour, pickup.block);
                log.push((
                    Level::Warn,
                    format!("The arm does not answer - leaving {block} for later"),
                ));
                self.phase = Phase::Choose;
                Tick::Again
            }
            Phase::Pickup(pickup) => {
                let (odd, colour) = (pickup.block, pickup.colour);
                let arm = self.arm.as_mut();
                match pickup.step(inputs, &self.config, &self.objects, &mut self.ctx, arm, log) {
                    PickEvent::Go(motion, gripper) => Tick::Out(motion, gripper),
                    PickEvent::Picked => {
                        log.push((Level::Success, format!("Picked up {}", name(colour, odd))));
                        self.held = Some(odd);
                        self.stamp(odd, t, 2);
                        self.phase = self.delivering(odd, colour, t);
                        Tick::Again
                    }
                    PickEvent::Demote => {
                        self.objects.demote(odd);
                        self.ctx.recoveries += 1;
                        self.demoted.insert(odd, t);
                        // A potential block again, with its looks to come: the ones that
                        // confirmed it before must not keep it from being looked at anew
                        // (the attempts at it stay bounded by MAX_BLOCK_ATTEMPTS).
                        self.explored.potential_looks.remove(&odd);
                        self.phase = Phase::BackOff(t);
                        Tick::Again
                    }
                    PickEvent::GiveUp => self.manual(Cause::Pickup),
                }
            }
            Phase::Deliver(delivery) => {
                let (odd, colour) = (delivery.block, delivery.colour);
                if let Some(gate) = self.objects.gate_for(colour) {
                    delivery.follow_gate(*gate, &self.config);
                }
                let arm = self.arm.as_mut();
                match delivery.step(inputs, &self.config, &mut self.ctx, arm, log) {
                    DropEvent::Go(motion, gripper) => Tick::Out(motion, gripper),
                    DropEvent::Delivered { at, slot } => {
                        self.objects.deliver(odd, at);
                        self.drop_slots.entry(colour).or_default().insert(slot);
                        self.held = None;
                        self.delivered_markers.extend([odd, odd + 1]);
                        self.stamp(odd, t, 3);
                        let of = match self.config.total_blocks {
                            0 => String::new(),
                            n => format!("/{n}"),
                        };
                        log.push((
                            Level::Success,
                            format!(
                                "Delivered {} ({}{of})",
                                name(colour, odd),
                                self.objects.delivered()
                            ),
                        ));
                        self.phase = Phase::Choose;
                        Tick::Again
                    }
                    DropEvent::Missed { why, slot, at } => {
                        // Not at its gate: found again like a new block, and picked up again;
                        // the place it was left is looked at from four sides till then.
                        // Whatever lies in its drop place, the next drop goes elsewhere.
                        self.drop_slots.entry(colour).or_default().insert(slot);
                        let robot = inputs.pose.position();
                        (self.explored.unexplained).push(Unexplained::new(at, robot, Some(odd)));
                        log.push((
                            Level::Warn,
                            format!(
                                "{} not delivered: {why} - looking for it again",
                                name(colour, odd)
                            ),
                        ));
                        self.held = None;
                        self.objects.forget(odd);
                        self.phase = Phase::Choose;
                        Tick::Again
                    }
                    DropEvent::GiveUp => self.manual(Cause::Delivery),
                    DropEvent::Full => self.manual(Cause::GateFull),
                }
            }
            Phase::BackOff(since) => {
                // A path planned from inside the block's ring would drive into it
                // (navdeck's, as after a drop). The map behind is the block's ring too, so
                // it is not asked: the robot crept in forwards from its staging point
                // (`staging_distance` away), and backs `back_off_time` x 0.1 m/s along
                // that way, no further than it came.
                if t - *since < self.config.back_off_time {
                    let back = Twist::new(-super::config::BACK_OFF_SPEED, 0.0);
                    return Tick::Out(Motion::Drive(back), None);
                }
                self.phase = Phase::Choose;
                Tick::Again
            }
            Phase::WaitArm if inputs.can_pick => {
                log.push((Level::Success, "The arm answers - choosing again".into()));
                self.phase = Phase::Choose;
                Tick::Again
            }
            Phase::WaitArm => Tick::Out(Motion::Stop, None),
            Phase::Done => Tick::Out(Motion::Stop, None),
            Phase::Manual => Tick::Out(Motion::Stop, None),
        }
    }

    /// Off to the gate with held block `odd`, or exploring on while its gate is unknown.
    /// With every drop place at its gate taken, the mission hands over: a block put down
    /// anywhere else would not be at its gate.
    pub(super) fn delivering(&mut self, odd: u32, colour: Colour, t: f64) -> Phase {
        let Some(&gate) = self.objects.gate_for(colour) else {
            return Phase::Choose;
        };
        let taken = self.drop_slots.get(&colour);
        let free: Vec<usize> = (0..DROP_PLACES.len())
            .filter(|s| taken.is_none_or(|t| !t.contains(s)))
            .collect();
        match Delivery::new(odd, colour, gate, free, &self.config, t) {
            Some(delivery) => Phase::Deliver(delivery),
            None => {
                self.handover = Some(Cause::GateFull.label());
                Phase::Manual
            }
        }
    }

    pub(super) fn manual(&mut self, cause: Cause) -> Tick {
        self.handover = Some(cause.label());
        self.phase = Phase::Manual;
        Tick::Out(Motion::Stop, None)
    }

    fn ignored(&self) -> Vec<u32> {
        let mut ids = self.delivered_markers.clone();
        if let Some(odd) = self.held {
            ids.extend([odd, odd + 1]);
        }
        ids
    }
}
