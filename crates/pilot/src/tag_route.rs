//! Route mode (seed 003): a tag map's task, or the way to one tag, driven through the
//! tag graph by the core's `RouteRun` (pure pursuit between tags, quarter turns,
//! alignment on the last tag), proposing to the arbiter below the collision monitor as
//! lane mode does. Every tag of the map seen resets the pose the console shows (seed 003
//! §2.5 step 4); a leg the collision monitor holds the robot on for `BLOCKED_AFTER_S` is
//! marked blocked and the rest routed round it by BFS, as `navdeck route` does.
//! `tag_route_drive.rs` holds the stepping; this file the state and the asks.

use crate::Pilot;
use crate::mode::Mode;
use navdeck_core::data::{Level, TagSighting};
use navdeck_core::geometry::{Point2, Pose2, Twist};
use navdeck_core::tags::drive::{DriveSetup, Phase, RouteRun};
use navdeck_core::tags::{TagId, TagMap};
use std::sync::Arc;

/// Seconds the collision monitor must hold the robot on a leg before the leg is marked
/// blocked (navdeck's: long enough for a person stepping across to pass).
pub const BLOCKED_AFTER_S: f64 = 2.0;
/// A route starts from the tag nearest the camera's floor point, if one lies this near,
/// metres (navdeck's: a robot off the graph is driven onto it by hand first).
pub const START_REACH: f64 = 0.5;

/// What route mode was asked to drive to.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum TagGoal {
    /// A task of the map by name: its waypoints in order (seed 003 §2.2 modes 1/2).
    Task(String),
    /// One tag, by the fewest edges (seed 003 §2.2 mode 3).
    Tag(TagId),
}

impl TagGoal {
    /// "task task1", "tag 205".
    pub fn label(&self) -> String {
        match self {
            TagGoal::Task(name) => format!("task {name}"),
            TagGoal::Tag(id) => format!("tag {id}"),
        }
    }
}

/// The last pose reset from a tag.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TagReset {
    pub t: f64,
    pub tag: TagId,
    pub pose: Pose2,
}

/// Route mode's state: the map, the goal, the run, and what the tag camera last saw.
#[derive(Clone, Debug, Default)]
pub struct TagRouting {
    pub(crate) map: Option<Arc<TagMap>>,
    pub(crate) setup: DriveSetup,
    pub(crate) goal: Option<TagGoal>,
    pub(crate) run: Option<RouteRun>,
    /// The newest frame's tags, for the screen.
    pub(crate) seen: Vec<TagSighting>,
    /// Tags from a frame not yet given to the driver.
    pub(crate) fresh: Option<Vec<TagSighting>>,
    pub(crate) last_reset: Option<TagReset>,
    /// Resets from tags so far.
    pub(crate) resets: u64,
    /// Since when the collision monitor has held the robot on a leg.
    pub(crate) held_since: Option<f64>,
    /// The driver's last step: when, and its command.
    pub(crate) last_step: Option<(f64, Twist)>,
    /// How the last run ended: done, or the failure naming its leg.
    pub(crate) outcome: Option<(Level, String)>,
}

impl TagRouting {
    /// The tag map on the floor, when one was given (`--tags`).
    pub fn map(&self) -> Option<&TagMap> {
        self.map.as_deref()
    }
    pub fn goal(&self) -> Option<&TagGoal> {
        self.goal.as_ref()
    }
    /// The run being driven (or the last one, done, failed or paused).
    pub fn run(&self) -> Option<&RouteRun> {
        self.run.as_ref()
    }
    /// The tags the newest frame showed.
    pub fn seen(&self) -> &[TagSighting] {
        &self.seen
    }
    pub fn last_reset(&self) -> Option<TagReset> {
        self.last_reset
    }
    pub fn resets(&self) -> u64 {
        self.resets
    }
    /// How the last run ended, if it has.
    pub fn outcome(&self) -> Option<&str> {
        self.outcome.as_ref().map(|(_, text)| text.as_str())
    }
    /// What the run is doing, in words: "driving leg 2 (101 → 102)".
    pub fn phase_text(&self) -> String {
        let Some(run) = &self.run else {
            return "idle: choose a task or a tag".into();
        };
        let route = run.route();
        match run.phase() {
            Phase::Drive { leg } => format!("driving {}", run.leg_label(leg)),
            Phase::Search { leg } => {
                let tag = route.legs.get(leg).map_or(0, |l| l.to);
                format!("searching for tag {tag} ({})", run.leg_label(leg))
            }
            Phase::Turn { leg, .. } => format!("turning for {}", run.leg_label(leg)),
            Phase::Align => format!("aligning on tag {}", self.last_tag()),
            Phase::BackOff { .. } => format!("backing off tag {} to come again", self.last_tag()),
            Phase::Done => format!("done on tag {}", self.last_tag()),
            Phase::Failed => "failed".into(),
        }
    }
    /// The leg being driven, as (index, from, to).
    pub fn current_leg(&self) -> Option<(usize, TagId, TagId)> {
        let run = self.run.as_ref()?;
        let leg = match run.phase() {
            Phase::Drive { leg } | Phase::Search { leg } | Phase::Turn { leg, .. } => leg,
            Phase::Align | Phase::BackOff { .. } => run.route().legs.len().checked_sub(1)?,
            Phase::Done | Phase::Failed => return None,
        };
        let l = run.route().legs.get(leg)?;
        Some((leg, l.from, l.to))
    }
    /// The tag the robot is heading for.
    pub fn next_tag(&self) -> Option<TagId> {
        match self.current_leg() {
            Some((_, _, to)) => Some(to),
            None => self
                .run
                .as_ref()
                .filter(|r| matches!(r.phase(), Phase::Align))
                .map(|_| self.last_tag()),
        }
    }
    fn last_tag(&self) -> TagId {
        let route = self.run.as_ref().map(|r| r.route());
        route.and_then(|r| r.tags.last().copied()).unwrap_or(0)
    }
    /// Whether a run is under way (not done, failed or never started).
    pub fn driving(&self) -> bool {
        self.run
            .as_ref()
            .is_some_and(|r| !matches!(r.phase(), Phase::Done | Phase::Failed))
    }
}

impl Pilot {
    /// Route mode's view: the map, the run, the tags seen, the last reset.
    pub fn tag_route(&self) -> &TagRouting {
        &self.tag_route
    }

    /// Lays the tag map route mode drives on, with the camera's mount and the gains
    /// (`setup`); None leaves route mode saying what to pass.
    pub fn set_tag_map(&mut self, map: Option<Arc<TagMap>>, setup: DriveSetup) {
        self.tag_route = TagRouting {
            map,
            setup,
            ..TagRouting::default()
        };
    }

    /// Why route mode cannot start, if it cannot.
    pub(crate) fn route_refusal(&self) -> Option<&'static str> {
        self.tag_route.map.is_none().then_some(
            "route mode needs a tag map: start navdeck with --tags FILE \
             (such as --tags maps/tag_warehouse.yaml)",
        )
    }

    /// Takes in the tags of the newest frame: each tag of the map resets the estimate
    /// (the EKF's; MCL and lidar SLAM keep their own), and the driver gets them at its
    /// next step.
    pub(crate) fn sense_tags(&mut self, t: f64, tags: &[TagSighting]) {
        self.tag_route.seen = tags.to_vec();
        self.tag_route.fresh = Some(tags.to_vec());
        let Some(map) = self.tag_route.map.clone() else {
            return;
        };
        let look = self.tag_route.setup.look;
        for s in tags {
            let Some(tag) = map.tags.get(&s.id) else {
                continue;
            };
            // Seed 003 §2.5 step 4: the pose from the tag, the heading's quarter from the
            // estimate so far.
            let hint = self.pose().theta;
            let pose = navdeck_core::tags::drive::pose_from_tag(tag, s, look, hint);
            self.reset_from_tag(pose);
            self.tag_route.last_reset = Some(TagReset { t, tag: s.id, pose });
            self.tag_route.resets += 1;
        }
    }

    /// `:route TASK`, `:route tag ID`, or enter on the route picker: plans the route from
    /// the tag under the robot and drives it in route mode. True when the robot's motion
    /// changed.
    pub(crate) fn go_tag_route(&mut self, goal: TagGoal) -> bool {
        if let Some(why) = self.route_refusal() {
            self.log(Level::Error, why);
            return false;
        }
        self.tag_route.goal = Some(goal.clone());
        self.tag_route.run = None;
        self.tag_route.outcome = None;
        if self.mode != Mode::Route {
            // Entering the mode plans (set_mode -> enter_route).
            return self.set_mode(Mode::Route);
        }
        self.plan_tag_route(None);
        true
    }

    /// Route mode entered: a paused run goes on from the tag nearest the robot, a goal
    /// not yet planned is planned, else the mode waits for a choice.
    pub(crate) fn enter_route(&mut self) {
        self.tag_route.last_step = None;
        self.tag_route.held_since = None;
        self.tag_route.fresh = None;
        match (&self.tag_route.goal, &self.tag_route.run) {
            (Some(_), None) => self.plan_tag_route(None),
            (Some(_), Some(run)) if self.tag_route.driving() => {
                let left = run.waypoints_left().to_vec();
                self.plan_tag_route(Some(left));
            }
            _ => self.log(
                Level::Info,
                "route mode: choose a task or a tag (up/down, enter; :route TASK, :route tag ID)",
            ),
        }
    }

    /// Plans the goal's route from the tag nearest the robot (through `left`, the
    /// waypoints a paused run had not reached, when given) and starts the run.
    fn plan_tag_route(&mut self, left: Option<Vec<TagId>>) {
        let (Some(map), Some(goal)) = (self.tag_route.map.clone(), self.tag_route.goal.clone())
        else {
            return;
        };
        let start = match self.tag_under_robot(&map) {
            Ok(start) => start,
            Err(why) => return self.route_failed(format!("{}: {why}", goal.label())),
        };
        let aims: Vec<TagId> = match (&left, &goal) {
            (Some(left), _) => left.clone(),
            (None, TagGoal::Tag(id)) => vec![*id],
            (None, TagGoal::Task(name)) => match map.tasks.get(name) {
                Some(waypoints) => waypoints.clone(),
                None => {
                    let names: Vec<&str> = map.tasks.keys().map(String::as_str).collect();
                    let why = format!(
                        "no task {name:?} in the tag map (tasks: {})",
                        names.join(", ")
                    );
                    return self.route_failed(why);
                }
            },
        };
        let waypoints = RouteRun::task_waypoints(start, &aims);
        let (pose, odom) = (self.pose(), self.odometry.pose());
        match RouteRun::new(&map, waypoints, self.tag_route.setup, pose, odom) {
            Ok(run) => {
                let tags: Vec<String> = run.route().tags.iter().map(|t| t.to_string()).collect();
                let how = if left.is_some() { "on" } else { "planned" };
                let text = format!(
                    "route {how}: {} by {} ({} legs)",
                    goal.label(),
                    tags.join(" → "),
                    run.route().legs.len()
                );
                self.log(Level::Info, text);
                self.tag_route.run = Some(run);
                self.tag_route.last_step = None;
            }
            Err(e) => self.route_failed(format!("{}: {e}", goal.label())),
        }
    }

    /// The tag nearest the camera's floor point, or why the robot is not on the graph.
    fn tag_under_robot(&self, map: &TagMap) -> Result<TagId, String> {
        let pose = self.pose();
        let (s, c) = pose.theta.sin_cos();
        let look = self.tag_route.setup.look;
        let centre = Point2::new(pose.x + look * c, pose.y + look * s);
        let nearest = (map.tags.iter())
            .map(|(&id, t)| (id, centre.distance(Point2::new(t.x, t.y))))
            .min_by(|a, b| a.1.total_cmp(&b.1));
        match nearest {
            Some((id, d)) if d <= START_REACH => Ok(id),
            Some((id, d)) => Err(format!(
                "route mode starts on a tag; the nearest, tag {id}, is {d:.2} m away (drive onto it first)"
            )),
            None => Err("the tag map has no tags".into()),
        }
    }

    /// A route that cannot be driven: said, and kept for the status panel; the robot
    /// stands in route mode until another choice.
    pub(crate) fn route_failed(&mut self, why: String) {
        let text = format!("route: {why}");
        self.log(Level::Error, text.clone());
        self.tag_route.outcome = Some((Level::Error, text));
        self.tag_route.last_step = None;
    }
}
