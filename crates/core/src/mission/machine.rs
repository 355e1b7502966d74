//! The mission state machine (seed 001 sections 7-8): scan, choose, explore, pick up,
//! deliver, recover. Driven only by `Inputs`; every time it keeps came in through them.

use super::arm_moves::ArmMoves;
use super::config::{LOST_SCAN_AFTER, MissionConfig, RELOCATE_STANDOFF};
use super::delivery::{Delivery, DropEvent};
use super::drive::Turn;
use super::leg::{Ctx, Leg, LegStep};
use super::objects::{Colour, Objects};
use super::pickup::{PickEvent, Pickup, name};
use super::step::{Inputs, Level, Motion, Outputs};
use crate::data::{GripperCommand, GripperState};
use crate::geometry::{Point2, Twist};
use crate::perception::markers::MarkerCategory;
use std::collections::{BTreeMap, BTreeSet};

/// What exploration is heading for.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Target {
    Frontier,
    /// Free space the camera has not looked at yet.
    Unseen,
    Marker(u32),
    /// A block seen by one marker only (odd marker).
    Potential(u32),
    /// An unexplained small object (index into `Mission::unexplained`).
    Object(usize),
}

/// A small object the lidar mapped and no marker explains, and the looks taken at it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Unexplained {
    pub at: Point2,
    /// Direction of the first look, from the object, radians; later looks turn 90° on.
    pub first: f64,
    pub looks: u32,
}

#[derive(Clone, Debug)]
pub(super) enum Phase {
    /// Before the first step.
    Start,
    Scan {
        turn: Turn,
        initial: bool,
    },
    Choose,
    Explore {
        leg: Leg,
        target: Target,
    },
    /// Seed 001 "Robot Lost": rotating until a marker comes into view, since the time
    /// given; after `lost_timeout` without markers, driving back towards the nearest
    /// landmark known (navdeck's).
    Lost(f64, Option<Leg>),
    /// Backing away from a block the approach lost sight of (the robot may stand in its
    /// lethal ring, facing it), since the time given; then choosing again.
    BackOff(f64),
    Pickup(Pickup),
    Deliver(Delivery),
    Done,
    Manual,
}

/// Why a mission handed the robot to manual control.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Cause {
    /// A goal it needed had no path, after every retry.
    Unreachable,
    /// No landmarks for `lost_timeout`.
    Lost,
    /// A block could not be picked up (no path to it, or the gripper kept missing).
    Pickup,
    /// A held block could not be delivered (no path to its gate).
    Delivery,
    /// Exploration was complete with found blocks left (their gate never seen).
    BlocksLeft,
}

impl Cause {
    pub fn label(self) -> &'static str {
        match self {
            Cause::Unreachable => "unreachable target",
            Cause::Lost => "lost",
            Cause::Pickup => "pickup failed",
            Cause::Delivery => "delivery failed",
            Cause::BlocksLeft => "blocks left without a gate",
        }
    }
}

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
    pub(super) visited_markers: Vec<u32>,
    pub(super) visited_goals: Vec<Point2>,
    /// Looks taken at each potential block (odd marker), from different sides.
    pub(super) potential_looks: BTreeMap<u32, u32>,
    /// Small objects the lidar mapped that no marker explained when first met.
    pub(super) unexplained: Vec<Unexplained>,
    /// Exploration goals (frontier points, marker IDs) the planner could not reach, and
    /// the rounds of turning and trying them again so far.
    pub(super) given_up: Vec<Point2>,
    pub(super) given_up_markers: Vec<u32>,
    pub(super) retry_rounds: u32,
    /// What the camera has looked at.
    pub(super) coverage: super::coverage::Coverage,
    /// The exploration targets the last choice weighed (frontiers, unseen space), for
    /// the map.
    pub(super) candidates: Vec<Point2>,
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
    /// Lost, the robot already went back to a landmark and scanned there.
    pub(super) relocated: bool,
    /// The arm that picks and places blocks, when the robot has one.
    pub(super) arm: Option<ArmMoves>,
}

/// What resuming says, and the markers whose landmarks the filter should drop.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Resumed {
    pub log: Vec<(Level, String)>,
    pub forget: Vec<u32>,
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
            visited_markers: Vec::new(),
            visited_goals: Vec::new(),
            potential_looks: BTreeMap::new(),
            unexplained: Vec::new(),
            given_up: Vec::new(),
            given_up_markers: Vec::new(),
            retry_rounds: 0,
            coverage: super::coverage::Coverage::default(),
            candidates: Vec::new(),
            handover: None,
            demoted: BTreeMap::new(),
            attempts: BTreeMap::new(),
            announced: BTreeSet::new(),
            timeline: Vec::new(),
            held: None,
            delivered_markers: Vec::new(),
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
        let fov = self.config.view_fov_deg.to_radians();
        (self.coverage).look(inputs.map, inputs.pose, self.config.view_range, fov);
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
        if exploring && self.deliverable(inputs.pose.position()).is_some() {
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
                    DropEvent::Delivered => {
                        self.objects.deliver(odd);
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
                    DropEvent::GiveUp => self.manual(Cause::Delivery),
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
            Phase::Done => Tick::Out(Motion::Stop, None),
            Phase::Manual => Tick::Out(Motion::Stop, None),
        }
    }

    /// Off to the gate with held block `odd`, or exploring on while its gate is unknown.
    fn delivering(&self, odd: u32, colour: Colour, t: f64) -> Phase {
        let Some(&gate) = self.objects.gate_for(colour) else {
            return Phase::Choose;
        };
        let slot = (self.objects.blocks())
            .filter(|b| b.delivered && b.colour == colour)
            .count();
        Phase::Deliver(Delivery::new(odd, colour, gate, slot, &self.config, t))
    }

    /// Takes the mission up again at `t` after the user drove the robot: the blocks and
    /// gates found and the deliveries stand; what to do next is chosen afresh from where
    /// the robot now is (a handover's cause and the targets given up are cleared: the user
    /// may have fixed what stopped it). A block held when the user took over goes on to
    /// its gate if the gripper still holds it (or cannot tell); otherwise it was put down
    /// somewhere and is forgotten, to be found again: its markers are returned so the
    /// filter can drop their old places.
    pub fn resume(&mut self, t: f64, gripper: Option<GripperState>) -> Resumed {
        let mut log = Vec::new();
        let mut forget = Vec::new();
        self.handover = None;
        self.relocated = false;
        self.retry_rounds = 0;
        self.given_up.clear();
        self.given_up_markers.clear();
        self.last_marker = t;
        self.phase = Phase::Choose;
        if let Some(odd) = self.held {
            let block = self.objects.blocks().find(|b| b.markers[0] == odd).copied();
            let holding = matches!(gripper, None | Some(GripperState::Holding));
            match block {
                Some(b) if holding => {
                    log.push((
                        Level::Info,
                        format!("Still holding {} - on to its gate", name(b.colour, odd)),
                    ));
                    self.phase = self.delivering(odd, b.colour, t);
                }
                _ => {
                    let what = block.map_or(format!("block {odd}"), |b| name(b.colour, odd));
                    log.push((
                        Level::Warn,
                        format!("{what} is no longer in the gripper - looking for it again"),
                    ));
                    self.held = None;
                    self.objects.forget(odd);
                    self.demoted.remove(&odd);
                    forget = vec![odd, odd + 1];
                }
            }
        }
        log.push((
            Level::Info,
            format!(
                "Mission resumed: {} delivered, {} more known",
                self.objects.delivered(),
                self.objects.blocks().filter(|b| !b.delivered).count()
            ),
        ));
        Resumed { log, forget }
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
