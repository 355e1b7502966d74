//! Driving a route of tags (seed 003 §2.3-§2.5): each leg by pure pursuit on the pose
//! carried from the last tag, a quarter turn where the next leg turns, the alignment on
//! the last tag; every tag seen resets the pose. A tag not seen where the map puts it is
//! sought by creeping on a little, then the leg fails with its name. One `step` a
//! control period; time and sightings come from the caller.

use super::control::{DriveGains, align_rate, aligned, pursuit, turn_done, turn_rate};
use super::reset::{PoseReference, TagSighting, over_point, pose_from_tag};
use crate::geometry::{Point2, Pose2, wrap_angle};
use crate::tags::file::{Direction, TagId, TagMap};
use crate::tags::graph::Route;

/// How the robot carries its camera and how it looks for tags.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DriveSetup {
    pub gains: DriveGains,
    /// The image centre's floor point, metres ahead of the robot's centre.
    pub look: f64,
    /// A tag within this of the image centre's floor point, along the way, has been
    /// reached (seed 003 §2.3: the tag's centre within ±50 px of the image's middle row).
    pub arrive_band: f64,
    /// How far past where the map puts a tag the robot creeps looking for it, metres,
    /// and how fast, m/s.
    pub search_distance: f64,
    pub creep_speed: f64,
    /// Tries at alignment before the task fails: each backs off and comes again.
    pub align_tries: u32,
}

impl Default for DriveSetup {
    fn default() -> Self {
        Self {
            gains: DriveGains::default(),
            look: 0.1,
            arrive_band: 0.02,
            search_distance: 0.3,
            creep_speed: 0.05,
            align_tries: 3,
        }
    }
}

/// What the driver is doing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Phase {
    /// Driving leg `leg` of the route.
    Drive {
        leg: usize,
    },
    /// The tag of leg `leg` was not where the map puts it: creeping on, looking.
    Search {
        leg: usize,
    },
    /// Turning in place to the heading of leg `leg`.
    Turn {
        leg: usize,
        target: f64,
    },
    /// Turning on the last tag until square to it.
    Align,
    /// Backing off the last tag, from where the estimate put the robot, to come at it
    /// again.
    BackOff {
        from: Point2,
    },
    Done,
    Failed,
}

/// What happened, for the log and the report.
#[derive(Clone, Debug, PartialEq)]
pub enum DriveEvent {
    /// The tag at the end of a leg was reached.
    Arrived { leg: usize, tag: TagId },
    /// A turn ended, `error` radians short of the heading it aimed at by the estimate.
    Turned { leg: usize, error: f64 },
    /// Square on the last tag: its angle and lateral offset as last seen.
    Aligned {
        tag: TagId,
        align: f64,
        lateral: f64,
    },
    /// The route was driven.
    Done,
    /// The route cannot go on: which leg and why.
    Failed { leg: usize, why: String },
}

/// A leg as driven: where the robot's centre should end, the heading it keeps, and
/// which way it travels.
#[derive(Clone, Copy, Debug, PartialEq)]
struct LegPlan {
    to: TagId,
    goal: Point2,
    heading: f64,
    backward: bool,
}

/// Drives one route.
#[derive(Clone, Debug)]
pub struct TagDriver {
    setup: DriveSetup,
    legs: Vec<LegPlan>,
    last_tag: TagId,
    phase: Phase,
    reference: PoseReference,
    /// Where the robot was when it began looking for a missing tag, by the estimate.
    search_from: Option<Point2>,
    /// Tries at alignment used.
    tries: u32,
    /// Control periods in a row the aligning tag was not in the frame, and the command
    /// before it went missing.
    align_unseen: u32,
    align_last: (f64, f64),
}

/// A real camera's frames come slower than control (a 15 Hz /rgb under a 30 Hz loop) and
/// now and then miss a tag: while aligning, a tag missing for up to this many control
/// periods holds the last turn for the first of them, then stands still; after them the
/// tag is lost.
const ALIGN_HOLD: u32 = 1;
const ALIGN_LOST: u32 = 15;

impl TagDriver {
    /// A driver for `route` on `map`, the robot at map pose `start` with the odometry
    /// at `odom`.
    pub fn new(map: &TagMap, route: &Route, setup: DriveSetup, start: Pose2, odom: Pose2) -> Self {
        let legs = (route.legs.iter())
            .filter_map(|leg| {
                let (a, b) = (map.tags.get(&leg.from)?, map.tags.get(&leg.to)?);
                let travel = (b.y - a.y).atan2(b.x - a.x);
                let backward = leg.direction == Direction::Backward;
                let heading = if backward {
                    wrap_angle(travel + std::f64::consts::PI)
                } else {
                    travel
                };
                // The centre stops `look` short of the tag along the heading.
                let stand = over_point(b.x, b.y, heading, setup.look);
                let goal = Point2::new(stand.x, stand.y);
                Some(LegPlan {
                    to: leg.to,
                    goal,
                    heading,
                    backward,
                })
            })
            .collect::<Vec<_>>();
        let last_tag = route.tags.last().copied().unwrap_or(map.dock);
        let phase = if legs.is_empty() {
            Phase::Align
        } else {
            Phase::Drive { leg: 0 }
        };
        let mut driver = Self {
            setup,
            legs,
            last_tag,
            phase,
            reference: PoseReference::new(start, odom),
            search_from: None,
            tries: 0,
            align_unseen: 0,
            align_last: (0.0, 0.0),
        };
        driver.phase = driver
            .turn_if_needed(0, start.theta)
            .unwrap_or(driver.phase);
        driver
    }

    pub fn phase(&self) -> Phase {
        self.phase
    }

    /// The pose on the map the driver believes, with the odometry at `odom`.
    pub fn estimate(&self, odom: Pose2) -> Pose2 {
        self.reference.estimate(odom)
    }

    /// One control period: the odometry now and the tags in view give the command
    /// (v m/s, ω rad/s) and what happened.
    pub fn step(
        &mut self,
        map: &TagMap,
        odom: Pose2,
        seen: &[TagSighting],
    ) -> ((f64, f64), Vec<DriveEvent>) {
        let mut events = Vec::new();
        // Every tag of the map in view resets the pose (seed 003 §2.5 step 4).
        let hint = self.reference.estimate(odom).theta;
        for s in seen {
            if let Some(tag) = map.tags.get(&s.id) {
                let pose = pose_from_tag(tag, s, self.setup.look, hint);
                self.reference = PoseReference::new(pose, odom);
            }
        }
        let est = self.reference.estimate(odom);
        let g = self.setup.gains;
        let command = match self.phase {
            Phase::Drive { leg } | Phase::Search { leg } => {
                let plan = self.legs[leg];
                let target = seen.iter().find(|s| s.id == plan.to);
                // Along the way the tag still lies ahead (+) of the image centre.
                let to_go = target.map(|s| if plan.backward { -s.ahead } else { s.ahead });
                if to_go.is_some_and(|d| d <= self.setup.arrive_band) {
                    events.push(DriveEvent::Arrived { leg, tag: plan.to });
                    self.search_from = None;
                    (self.align_unseen, self.align_last) = (0, (0.0, 0.0));
                    self.phase = self.after_leg(leg, est.theta);
                    (0.0, 0.0)
                } else {
                    self.drive_leg(leg, plan, est, &mut events)
                }
            }
            Phase::Turn { leg, target } => {
                let error = wrap_angle(target - est.theta);
                if turn_done(&g, error) {
                    events.push(DriveEvent::Turned { leg, error });
                    self.phase = Phase::Drive { leg };
                    (0.0, 0.0)
                } else {
                    (0.0, turn_rate(&g, error))
                }
            }
            Phase::Align => match seen.iter().find(|s| s.id == self.last_tag) {
                Some(s) => {
                    self.align_unseen = 0;
                    if aligned(&g, s.align, s.lateral) {
                        events.push(DriveEvent::Aligned {
                            tag: s.id,
                            align: s.align,
                            lateral: s.lateral,
                        });
                        events.push(DriveEvent::Done);
                        self.phase = Phase::Done;
                        (0.0, 0.0)
                    } else if align_rate(&g, s.align) == 0.0 {
                        // Square but to one side: a turn cannot mend that; back off and
                        // come at the tag again (navdeck's, the seed has no law here).
                        self.back_off(est, &mut events)
                    } else {
                        self.align_last = (0.0, align_rate(&g, s.align));
                        self.align_last
                    }
                }
                None if self.align_unseen < ALIGN_LOST => {
                    self.align_unseen += 1;
                    if self.align_unseen <= ALIGN_HOLD {
                        self.align_last
                    } else {
                        (0.0, 0.0)
                    }
                }
                None => self.fail(
                    self.legs.len().saturating_sub(1),
                    format!(
                        "tag {} went out of view while aligning on it",
                        self.last_tag
                    ),
                    &mut events,
                ),
            },
            Phase::BackOff { from } => {
                let leg = self.legs.len() - 1;
                let plan = self.legs[leg];
                if from.distance(Point2::new(est.x, est.y)) >= 2.0 * self.setup.search_distance {
                    self.phase = Phase::Drive { leg };
                    (0.0, 0.0)
                } else {
                    let back = if plan.backward { 1.0 } else { -1.0 };
                    (back * self.setup.creep_speed * 2.0, 0.0)
                }
            }
            Phase::Done | Phase::Failed => (0.0, 0.0),
        };
        (command, events)
    }

    /// Pure pursuit along leg `leg` on the estimate; past where the map puts its tag
    /// without seeing it, creep on looking, then fail.
    fn drive_leg(
        &mut self,
        leg: usize,
        plan: LegPlan,
        est: Pose2,
        events: &mut Vec<DriveEvent>,
    ) -> (f64, f64) {
        let g = self.setup.gains;
        let (s, c) = est.theta.sin_cos();
        let (dx, dy) = (plan.goal.x - est.x, plan.goal.y - est.y);
        // The goal in the robot frame (x ahead, y left), then in the frame it travels in
        // (turned half round going backward), as ahead and right.
        let (gx, gy) = (c * dx + s * dy, -s * dx + c * dy);
        let (ahead, right, gain, sense) = if plan.backward {
            (-gx, gy, g.gain_backward, -1.0)
        } else {
            (gx, -gy, g.gain_forward, 1.0)
        };
        let here = Point2::new(est.x, est.y);
        if ahead < -self.setup.arrive_band || self.search_from.is_some() {
            let from = *self.search_from.get_or_insert(here);
            self.phase = Phase::Search { leg };
            if from.distance(here) > self.setup.search_distance {
                let why = format!(
                    "tag {} not seen within {:.2} m past where the map puts it",
                    plan.to, self.setup.search_distance
                );
                return self.fail(leg, why, events);
            }
            return (sense * self.setup.creep_speed, 0.0);
        }
        (sense * g.speed, pursuit(&g, ahead, right, gain))
    }

    /// After reaching the tag of leg `leg`: align on it if it was the last, else turn if
    /// the next leg goes another way, else drive on.
    fn after_leg(&self, leg: usize, heading: f64) -> Phase {
        if leg + 1 >= self.legs.len() {
            return Phase::Align;
        }
        self.turn_if_needed(leg + 1, heading)
            .unwrap_or(Phase::Drive { leg: leg + 1 })
    }

    /// A quarter (or half) turn before leg `leg` when it goes more than 45° off
    /// `heading`; pure pursuit takes smaller differences in its stride.
    fn turn_if_needed(&self, leg: usize, heading: f64) -> Option<Phase> {
        let target = self.legs.get(leg)?.heading;
        (wrap_angle(target - heading).abs() > std::f64::consts::FRAC_PI_4)
            .then_some(Phase::Turn { leg, target })
    }

    fn back_off(&mut self, est: Pose2, events: &mut Vec<DriveEvent>) -> (f64, f64) {
        if self.tries + 1 >= self.setup.align_tries {
            let why = format!(
                "square on tag {} but still to its side after {} tries",
                self.last_tag, self.setup.align_tries
            );
            return self.fail(self.legs.len().saturating_sub(1), why, events);
        }
        if self.legs.is_empty() {
            return self.fail(
                0,
                format!(
                    "to one side of tag {} with no leg to come again along",
                    self.last_tag
                ),
                events,
            );
        }
        self.tries += 1;
        self.phase = Phase::BackOff {
            from: Point2::new(est.x, est.y),
        };
        (0.0, 0.0)
    }

    fn fail(&mut self, leg: usize, why: String, events: &mut Vec<DriveEvent>) -> (f64, f64) {
        events.push(DriveEvent::Failed { leg, why });
        self.phase = Phase::Failed;
        (0.0, 0.0)
    }
}
