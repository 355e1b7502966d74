//! Picking a block up (seed 001 section 8 "Pickup Sequence"): path to a staging point,
//! open, face the block, creep up to it, close, and check the gripper holds it. With an
//! arm (seed 000 section 6), the creep stops with the block in the arm's reach, and the
//! arm goes above the block, descends, closes and lifts.

use super::arm_moves::{ABOVE, ArmMove, ArmMoves, arrived};
use super::block_fit::{lidar_centre, scan_centre};
use super::config::{BLOCK_LOST_AFTER, CAMERA_HALF_FOV, CAMERA_RANGE, FIT_SEARCH, MissionConfig};
use super::drive::{Pace, Wait, bearing, creep_twist, faces, opened, towards, turn_towards};
use super::leg::{Ctx, Leg, LegStep};
use super::objects::{Block, Colour, Objects};
use super::step::{Inputs, Level, Motion};
use crate::data::{GripperCommand, GripperState};
use crate::geometry::{Point2, Twist};
use crate::map::costmap::{Costmap, is_lethal};

/// Where a pick-up is.
#[derive(Clone, Debug)]
enum Stage {
    Travel(Leg),
    Open,
    Face,
    /// Creeping in at a pace that only ever slows.
    Approach(Pace),
    Close,
    /// After an empty close: open again before the retry.
    Reopen,
    /// Back away a little so the retry approaches straight.
    BackUp,
    /// The arm's tool to above the block, then down to it.
    ArmAbove(ArmMove),
    ArmDown(ArmMove),
    /// The arm, holding the block, up to its carrying pose.
    Lift(ArmMove),
    /// The arm, empty after a miss, up before the robot backs away.
    ArmUp(ArmMove),
}

/// A scan's outline of the block stands this long after the block left the scan (seconds,
/// navdeck's): more than a creep takes over the last 10 cm before the jaws (5 cm at each
/// of its speeds), where a lidar's least range hides it.
const OUTLINE_KEPT: f64 = 2.0;

/// The arm's carrying pose.
const CARRY: &str = "home";

/// What a pick-up step comes to.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum PickEvent {
    Go(Motion, Option<GripperCommand>),
    Picked,
    /// Missed twice or lost from view: back to a potential block.
    Demote,
    GiveUp,
}

/// A pick-up under way.
#[derive(Clone, Debug)]
pub(crate) struct Pickup {
    pub block: u32,
    pub colour: Colour,
    stage: Stage,
    since: f64,
    retried: bool,
    /// When the block's markers were last seen, or last not expected in view.
    last_seen: f64,
    /// The block's centre from the newest scan's outline of it, and when that was fitted.
    outline: Option<(Point2, f64)>,
    /// Where an outline (the scan's or the map's) last put the block near it: the map's
    /// outline is looked for round it, not round the markers' estimate, which may lie at
    /// the edge of the search, a few centimetres away.
    last_fit: Option<Point2>,
}

/// Where the path to a block ends: `staging_distance` from it towards where the robot was
/// when the camera last read one of its markers (a block's markers sit on two adjacent
/// faces, readable only from their side; from the other two it cannot be told from a box),
/// else towards the robot. If that spot or the straight run in from it is blocked (a block
/// by a wall or a box), the nearest direction round the block, in 30 degree steps, where
/// both are clear.
fn staging_point(
    block: Point2,
    seen_from: Option<Point2>,
    robot: Point2,
    map: &Costmap,
    config: &MissionConfig,
) -> Point2 {
    let from = seen_from.unwrap_or(robot);
    let toward = (from.y - block.y).atan2(from.x - block.x);
    let clear = |p: Point2| !is_lethal(map.at(p));
    // The last few centimetres are the block's own lethal ring: not checked.
    let inner = config.grip_distance + 0.08;
    (0..12)
        .map(|k| {
            let turn = f64::from((k + 1) / 2) * 30f64.to_radians();
            toward + if k % 2 == 1 { turn } else { -turn }
        })
        .map(|a| (a.cos(), a.sin()))
        .find(|&(c, s)| {
            let at = |d: f64| Point2::new(block.x + d * c, block.y + d * s);
            let steps = ((config.staging_distance - inner) / map.resolution).ceil() as usize;
            (0..=steps).all(|i| clear(at(inner + i as f64 * map.resolution)))
        })
        .map_or_else(
            || towards(block, from, config.staging_distance),
            |(c, s)| {
                Point2::new(
                    block.x + config.staging_distance * c,
                    block.y + config.staging_distance * s,
                )
            },
        )
}

impl Pickup {
    /// A pick-up of `block`, whose markers the camera last read with the robot at
    /// `seen_from` (if it has), starting with the robot at `robot`.
    pub fn new(
        block: &Block,
        seen_from: Option<Point2>,
        robot: Point2,
        map: &Costmap,
        config: &MissionConfig,
        t: f64,
    ) -> Self {
        let goal = staging_point(block.position, seen_from, robot, map, config);
        let label = name(block.colour, block.markers[0]);
        Self {
            block: block.markers[0],
            colour: block.colour,
            stage: Stage::Travel(Leg::new(goal, label)),
            since: t,
            retried: false,
            last_seen: t,
            outline: None,
            last_fit: None,
        }
    }

    /// Where the lidar's live outline puts the block while the robot is near it (facing
    /// it, creeping up to it or gripping it): from the newest scan, or from the last scan
    /// that outlined it within `OUTLINE_KEPT` (the block may be under the lidar's least
    /// range by then); `None` while travelling or without an outline.
    pub fn outline(&self) -> Option<Point2> {
        self.outline.map(|(at, _)| at)
    }

    /// Whether the arm is at work on the block (reaching, gripping, lifting): a pick
    /// that has not got there may be left for later.
    pub fn arm_engaged(&self) -> bool {
        matches!(
            self.stage,
            Stage::ArmAbove(_)
                | Stage::ArmDown(_)
                | Stage::Lift(_)
                | Stage::ArmUp(_)
                | Stage::Close
        )
    }

    pub fn label(&self) -> String {
        let what = match &self.stage {
            Stage::Travel(leg) if leg.retrying().is_some() => "no path: retry to",
            Stage::Travel(_) => "travel to",
            Stage::Open => "open gripper for",
            Stage::Face => "face",
            Stage::Approach(_) => "approach",
            Stage::Close => "grip",
            Stage::Reopen => "reopen for",
            Stage::BackUp => "back up from",
            Stage::ArmAbove(_) => "arm above",
            Stage::ArmDown(_) => "arm down to",
            Stage::Lift(_) => "lift",
            Stage::ArmUp(_) => "arm up from",
        };
        format!("{what} {}", name(self.colour, self.block))
    }

    fn enter(&mut self, stage: Stage, t: f64) {
        self.stage = stage;
        self.since = t;
        self.last_seen = t;
    }

    pub fn step(
        &mut self,
        inputs: &Inputs,
        config: &MissionConfig,
        objects: &Objects,
        ctx: &mut Ctx,
        arm: Option<&mut ArmMoves>,
        log: &mut Vec<(Level, String)>,
    ) -> PickEvent {
        let Some(block) = objects.blocks().find(|b| b.markers[0] == self.block) else {
            return PickEvent::Demote;
        };
        let (t, pose) = (inputs.t, inputs.pose);
        // The lidar's outline of the block, where it has one, places it more finely than
        // its markers do; only the stages near the block use where it is. The newest scan
        // outlines it in the robot's own frame, free of any error in the pose the map was
        // built with; the map's outline stands in when no scan shows it.
        let near = !matches!(self.stage, Stage::Travel(_));
        let size = config.block_size;
        let live = near
            .then(|| scan_centre(inputs.scan, pose, block.position, size, FIT_SEARCH))
            .flatten();
        self.outline = match live {
            Some(centre) => Some((centre, t)),
            None => (self.outline).filter(|(_, fitted)| near && t - fitted <= OUTLINE_KEPT),
        };
        let around = self.last_fit.unwrap_or(block.position);
        let mapped = || {
            let (map, occupied, robot) = (inputs.map, inputs.occupied, pose.position());
            lidar_centre(map, occupied, around, size, FIT_SEARCH, robot)
        };
        let fitted = near.then(|| self.outline().or_else(mapped)).flatten();
        self.last_fit = fitted.or(self.last_fit.filter(|_| near));
        let aim = fitted.unwrap_or(block.position);
        let distance = pose.position().distance(aim);
        let error = bearing(pose, aim);
        let waited = t - self.since;
        let stop = PickEvent::Go(Motion::Stop, None);
        // With an arm the robot stops short, the block in the arm's reach.
        let mid = config.block_size / 2.0;
        let mut arm = arm;
        let grip_at = (arm.as_mut()).map_or(config.grip_distance, |a| {
            a.reach_from_centre(config.arm_standoff, mid)
        });
        let joints = inputs.arm;
        if matches!(self.stage, Stage::Face | Stage::Approach(_)) {
            // Seed 001 "Block Lost During Approach": in view but unseen for 3 s (navdeck's
            // figure; the seed gives none). Nearer than the camera's blind distance the
            // block is under its view, not lost.
            let blind = config.blind_distance.unwrap_or(0.0);
            let in_view =
                (blind..=CAMERA_RANGE).contains(&distance) && error.abs() < CAMERA_HALF_FOV;
            let spotted =
                inputs.camera_frame && block.markers.iter().any(|m| inputs.seen.contains(m));
            // A scan that outlines it says it is there even when its markers, on two
            // faces only, face away from this approach.
            if spotted || !in_view || live.is_some() {
                self.last_seen = t;
            } else if t - self.last_seen >= BLOCK_LOST_AFTER {
                log.push((
                    Level::Warn,
                    format!(
                        "Lost {} during the approach - back to a potential block",
                        name(self.colour, self.block)
                    ),
                ));
                return PickEvent::Demote;
            }
        }
        match &mut self.stage {
            Stage::Travel(leg) => match leg.step(inputs, config, ctx, log) {
                LegStep::Move(motion) => PickEvent::Go(motion, None),
                LegStep::Arrived => {
                    self.enter(Stage::Open, t);
                    PickEvent::Go(Motion::Stop, Some(GripperCommand::Open))
                }
                LegStep::GiveUp | LegStep::Unreachable(_) => PickEvent::GiveUp,
            },
            Stage::Open | Stage::Reopen => match opened(inputs.gripper, waited, config) {
                Wait::Waiting => stop,
                outcome => {
                    if outcome == Wait::TimedOut {
                        log.push((Level::Warn, "Gripper did not report open".into()));
                    }
                    let next = match (&self.stage, arm) {
                        (Stage::Open, _) => Stage::Face,
                        (_, Some(arm)) => Stage::ArmUp(arm.go_to_pose(CARRY, joints)),
                        (_, None) => Stage::BackUp,
                    };
                    self.enter(next, t);
                    stop
                }
            },
            Stage::Face => {
                if faces(error) {
                    self.enter(Stage::Approach(Pace::new()), t);
                    return stop;
                }
                PickEvent::Go(Motion::Drive(turn_towards(error, config)), None)
            }
            Stage::Approach(pace) => {
                let creep = (config.staging_distance - grip_at).abs() / config.approach_speed;
                if distance <= grip_at || waited >= 2.0 * creep + 2.0 {
                    let Some(arm) = arm else {
                        self.enter(Stage::Close, t);
                        return PickEvent::Go(Motion::Stop, Some(GripperCommand::Close));
                    };
                    return match arm.over(aim, mid + ABOVE, pose, joints) {
                        Ok(m) => {
                            let block = name(self.colour, self.block);
                            log.push((Level::Info, format!("Arm above {block}")));
                            self.enter(Stage::ArmAbove(m), t);
                            stop
                        }
                        Err(why) => {
                            let block = name(self.colour, self.block);
                            log.push((Level::Warn, format!("The arm cannot reach {block}: {why}")));
                            self.missed(t, ctx, log)
                        }
                    };
                }
                let speed = pace.speed(distance - grip_at, config);
                PickEvent::Go(Motion::Drive(creep_twist(speed, error, config)), None)
            }
            Stage::ArmAbove(m) => {
                if !arrived(m, joints, waited) {
                    return stop;
                }
                let Some(arm) = arm else { return stop };
                match arm.lower_to(mid, joints) {
                    Ok(m) => self.enter(Stage::ArmDown(m), t),
                    Err(why) => {
                        log.push((Level::Warn, format!("The arm cannot descend: {why}")));
                        return self.missed(t, ctx, log);
                    }
                }
                stop
            }
            Stage::ArmDown(m) => {
                if !arrived(m, joints, waited) {
                    return stop;
                }
                self.enter(Stage::Close, t);
                PickEvent::Go(Motion::Stop, Some(GripperCommand::Close))
            }
            Stage::Lift(m) | Stage::ArmUp(m) => {
                if !arrived(m, joints, waited) {
                    return stop;
                }
                if matches!(self.stage, Stage::Lift(_)) {
                    return PickEvent::Picked;
                }
                self.enter(Stage::BackUp, t);
                stop
            }
            Stage::Close => match inputs.gripper {
                Some(GripperState::Holding) => match arm {
                    Some(arm) => {
                        let block = name(self.colour, self.block);
                        log.push((Level::Info, format!("Lifting {block}")));
                        self.enter(Stage::Lift(arm.go_to_pose(CARRY, joints)), t);
                        stop
                    }
                    None => PickEvent::Picked,
                },
                // A gripper that reports nothing: after seed 001's wait, the block's markers
                // still in view mean it was not picked up (seed 001 "Gripper Failure").
                None if waited >= config.gripper_wait => {
                    let markers = [self.block, self.block + 1];
                    if inputs.camera_frame && inputs.seen.iter().any(|id| markers.contains(id)) {
                        self.missed(t, ctx, log)
                    } else {
                        PickEvent::Picked
                    }
                }
                Some(GripperState::Closed) => self.missed(t, ctx, log),
                _ if waited >= config.gripper_wait + 1.0 => self.missed(t, ctx, log),
                _ => stop,
            },
            Stage::BackUp => {
                if distance >= grip_at + 0.1 || waited >= 4.0 {
                    self.enter(Stage::Face, t);
                    return stop;
                }
                PickEvent::Go(Motion::Drive(Twist::new(-config.approach_speed, 0.0)), None)
            }
        }
    }

    /// The gripper closed on nothing: reopen and retry once, then give the block up.
    fn missed(&mut self, t: f64, ctx: &mut Ctx, log: &mut Vec<(Level, String)>) -> PickEvent {
        let block = name(self.colour, self.block);
        if self.retried {
            log.push((
                Level::Error,
                format!("Gripper missed {block} again - back to a potential block"),
            ));
            return PickEvent::Demote;
        }
        self.retried = true;
        ctx.recoveries += 1;
        log.push((
            Level::Warn,
            format!("Gripper closed on nothing - reopening to retry {block}"),
        ));
        self.enter(Stage::Reopen, t);
        PickEvent::Go(Motion::Stop, Some(GripperCommand::Open))
    }
}

/// "red block 421".
pub(crate) fn name(colour: Colour, odd: u32) -> String {
    format!("{} block {odd}", colour.label())
}

#[cfg(test)]
mod tests;
