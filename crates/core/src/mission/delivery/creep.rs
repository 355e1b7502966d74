//! The creep into a drop place (seed 001 section 8 "Delivery Sequence": drive forward,
//! release): along the drop place's line, the gate's normal through it, until the drop
//! place's depth, something the carried block would reach, or a stall.

use super::{Delivery, DropEvent, Stage, backing_off, opening, stopped};
use crate::geometry::{Point2, Pose2};
use crate::mission::arm_moves::ArmMoves;
use crate::mission::clearance::clear_ahead;
use crate::mission::config::MissionConfig;
use crate::mission::drive::{Pace, SLOW_FOR, bearing, creep_twist};
use crate::mission::drop_places::AT_GATE;
use crate::mission::objects::Gate;
use crate::mission::pickup::name;
use crate::mission::step::{Inputs, Level, Motion};

/// How far ahead of the robot's centre a carried block's centre lies, metres.
const CARRIED_AHEAD: f64 = 0.10;
/// The creep stops when the lidar's map has something this near ahead of the robot's
/// centre (metres): the carried block's far face (0.14 m ahead, clearance.rs) 2 cm from
/// it, the nearest the look starts (clearance.rs HELD_ZONE). Scans folded in from poses a
/// centimetre or two apart map a wall a few centimetres in front of where it is; a look
/// further out stopped first-row drops 2-4 cm short, and a block delivered in the row
/// nearer the wall stops a second-row creep before the loads touch.
const LOOK_AHEAD: f64 = 0.16;
/// The creep looks this much further than `LOOK_AHEAD`, so it is slow before what it
/// would stop at: its slow last `SLOW_FOR`, the centimetre braking onto it, and a step.
const SLOW_LOOK: f64 = SLOW_FOR + 0.03;
/// A creep stopped short lets the block go only where its centre lies this much inside
/// the gate's region, else tries another drop place: the estimate of the block against
/// the gate's is good to a few centimetres, and a block at the region's edge may be on
/// either side of it (metres; every drop place lies 0.04 m inside, drop_places.rs).
const STOPPED_SHORT_INSIDE: f64 = 0.03;

impl Delivery {
    /// One step of the creep (in `Stage::Forward`, which keeps its headway).
    pub(super) fn creep(
        &mut self,
        inputs: &Inputs,
        config: &MissionConfig,
        arm: Option<&mut ArmMoves>,
        log: &mut Vec<(Level, String)>,
    ) -> DropEvent {
        let (t, pose) = (inputs.t, inputs.pose);
        let distance = pose.position().distance(self.place.center);
        let creep = (config.drop_staging - config.drop_distance) / config.approach_speed;
        let stop_at = config.drop_distance + self.depth;
        // The wall (or a block delivered earlier) as the lidar mapped it stops the creep
        // too, wherever the markers put the gate. Only what the carried block would touch
        // counts: a block delivered in the row nearer the wall is passed beside.
        // Looked along the drop place's line, where the creep takes the load, rather than
        // along a heading that swings a few degrees as it steers onto that line.
        let along = Pose2::new(pose.x, pose.y, self.place.facing());
        let ahead = clear_ahead(inputs.map, inputs.occupied, along, LOOK_AHEAD + SLOW_LOOK);
        let blocked = ahead.is_some_and(|d| d <= LOOK_AHEAD + 1e-9);
        let remaining = (distance - stop_at).min(ahead.map_or(f64::INFINITY, |d| d - LOOK_AHEAD));
        let (stalled, speed) = match &mut self.stage {
            Stage::Forward(progress) => (
                progress.stalled(distance, t),
                progress.pace.speed(remaining, config),
            ),
            _ => (false, config.approach_speed),
        };
        let timed_out = t - self.since >= 2.0 * creep + 2.0;
        if distance <= stop_at || blocked || stalled || timed_out {
            let off = carried_at(pose).distance(self.gate.center);
            if distance > stop_at && off >= AT_GATE - STOPPED_SHORT_INSIDE {
                let gate = self.colour.label();
                let Some(next) = self.next_slot(inputs.map, config) else {
                    // Let go here, the block might lie on either side of the region's
                    // edge: neither "delivered" nor "not delivered" would be sure. It stays
                    // held.
                    log.push((
                        Level::Warn,
                        format!(
                            "No drop place left at the {gate} gate where the block would surely count - keeping it"
                        ),
                    ));
                    return DropEvent::Full;
                };
                log.push((
                    Level::Warn,
                    format!(
                        "Stopped {off:.2} m from the {gate} gate's centre, not well inside its {AT_GATE} m - trying drop place {}",
                        next + 1
                    ),
                ));
                self.enter(Stage::Withdraw(next), t);
                return backing_off();
            }
            let lower = arm.map(|a| a.lower_to(config.block_size / 2.0, inputs.arm));
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
                    return opening();
                }
                None => {
                    self.enter(Stage::Open, t);
                    return opening();
                }
            }
            return stopped();
        }
        let error = bearing(pose, onto_line(&self.place, pose.position()));
        let twist = creep_twist(speed, error, config);
        DropEvent::Go(Motion::Drive(twist), None)
    }
}

/// How far a creep gets, when it last got nearer, and its pace: the contact guard may hold
/// it a centimetre short of its stop, beside a block delivered earlier.
#[derive(Clone, Copy, Debug)]
pub(super) struct Progress {
    nearest: f64,
    at: f64,
    pace: Pace,
}

/// A creep that came no nearer than this in `STALL_TIME` has stopped (metres, seconds):
/// at `approach_speed` (0.05 m/s) it would have come 10 cm nearer, and the collision
/// monitor's stop holds it for a second at a time.
const STALL_MOVE: f64 = 0.005;
const STALL_TIME: f64 = 2.0;

impl Progress {
    pub(super) fn new(t: f64) -> Self {
        Self {
            nearest: f64::INFINITY,
            at: t,
            pace: Pace::new(),
        }
    }

    /// Notes the distance left at `t`; whether the creep has stopped getting nearer.
    fn stalled(&mut self, distance: f64, t: f64) -> bool {
        if distance < self.nearest - STALL_MOVE {
            (self.nearest, self.at) = (distance, t);
        }
        t - self.at >= STALL_TIME
    }
}

/// The creep aims at the point this far ahead on the drop place's line (metres): a robot
/// that arrived at its staging point a few centimetres to one side is back on the line
/// within a few times this (seed 003 §1.2.4: α = atan2(−lateral, L)).
const LINE_AHEAD: f64 = 0.10;

/// The point a robot at `at` aims at to come onto `place`'s line (its normal through its
/// centre) on the way in: `LINE_AHEAD` nearer the gate than the robot's foot on the line.
fn onto_line(place: &Gate, at: Point2) -> Point2 {
    let (dx, dy) = (at.x - place.center.x, at.y - place.center.y);
    place.in_front(dx * place.normal.0 + dy * place.normal.1 - LINE_AHEAD)
}

/// Where the carried block's centre is with the robot at `pose`.
pub(super) fn carried_at(pose: Pose2) -> Point2 {
    pose.transform_point(Point2::new(CARRIED_AHEAD, 0.0))
}
