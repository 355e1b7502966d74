//! Thinking and path-following modes: the goal cursor, planning on the robot's map,
//! following the planned path, replanning when it is blocked, and arrival.

use super::Pilot;
use super::mode::Mode;
use navdeck_core::control::follower::FollowStatus;
use navdeck_core::data::Level;
use navdeck_core::geometry::{Point2, Pose2, Rms, Twist};
use navdeck_core::map::costmap::is_lethal;
use navdeck_core::map::reach::{approach_point, escape_map};
use navdeck_core::perception::markers::MarkerCategory;
use navdeck_core::plan::pipeline::Plan;

mod guard;
mod views;

/// Seed 001 "Path Recalculation": at most one replan per this many seconds.
pub(super) const REPLAN_EVERY: f64 = 0.5;
/// Seed 001: replan when a new obstacle appears within 1 m of the path, a block within 0.5 m.
const NEW_OBSTACLE_NEAR: f64 = 1.0;
const NEW_BLOCK_NEAR: f64 = 0.5;
/// Seed 001 section 8: the robot approaches a block to 12 cm.
const BLOCK_APPROACH: f64 = 0.12;
/// Other landmarks: the goal stays this far beyond the edge of their lethal ring, metres.
const APPROACH_MARGIN: f64 = 0.05;

/// Where the user asked to go.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Target {
    Point(Point2),
    /// A goal pose (RViz's "2D Goal Pose", `:goto X Y THETA_DEG`): the point, then its heading.
    Pose(Pose2),
    /// A landmark: the goal is its approach point, worked out again at every replan
    /// because the map round the landmark fills in as the robot comes closer.
    Marker(u32),
}

impl Target {
    /// How the log and the status panel name it: "(1.20, -0.50)" or "marker 421".
    pub fn label(self) -> String {
        match self {
            Target::Point(p) => format!("({:.2}, {:.2})", p.x, p.y),
            Target::Pose(p) => format!(
                "({:.2}, {:.2}) facing {:.0}°",
                p.x,
                p.y,
                p.theta.to_degrees()
            ),
            Target::Marker(id) => format!("marker {id}"),
        }
    }

    /// The heading to end with, for a goal pose.
    pub fn heading(self) -> Option<f64> {
        match self {
            Target::Pose(p) => Some(p.theta),
            _ => None,
        }
    }
}

/// A planned path and where it leads.
#[derive(Clone, Debug)]
pub struct Route {
    pub target: Target,
    /// The point the path ends at.
    pub goal: Point2,
    pub label: String,
    pub plan: Plan,
}

/// What the following is doing, for the status panel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FollowView {
    pub remaining: f64,
    pub eta: f64,
    pub cross_track: f64,
}

/// Navigation state the pilot keeps.
#[derive(Debug, Default)]
pub(super) struct Navigation {
    /// The planner, with its search buffers kept between plans.
    pub planner: navdeck_core::plan::pipeline::Planner,
    pub route: Option<Route>,
    pub following: Option<FollowView>,
    pub arrived: bool,
    /// The map revision the route was last checked against, and when it was last replanned.
    pub checked_revision: u64,
    pub last_replan: f64,
    /// Paths planned again because the map changed under them, and the landmarks known
    /// when the path was last checked.
    pub replans: usize,
    pub landmarks_checked: std::collections::BTreeSet<u32>,
    /// The last follower command and when it was computed.
    pub last_step: Option<(f64, Twist)>,
    /// The contact guard stopped the robot at the last step: following a path, and in a
    /// motion the mission drives itself.
    pub in_contact: bool,
    pub drive_in_contact: bool,
    /// Cross-track error of the twin's true pose, and of the estimated pose (the
    /// follower's own), over every path since following started.
    pub true_cross_track: Rms,
    pub cross_track: Rms,
    /// The queued waypoints (Nav2's waypoint following) and the progress along them.
    pub waypoints: super::waypoints::Waypoints,
    /// The keepout and speed zones.
    pub zones: super::zones::Zones,
}

/// What a failed plan does to the path there was before it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum OnFailure {
    /// A replan, or a route's next waypoint: the old path is no longer any use.
    Drop,
    /// A new goal: refused, the old path (and its following) goes on.
    Keep,
}

impl Pilot {
    /// Plans from the robot's estimated position to `target`; logs the outcome. A
    /// failure drops the old path.
    pub(super) fn plan_route(&mut self, target: Target) -> bool {
        self.plan_or(target, OnFailure::Drop)
    }

    /// A new goal from the user: planned as `plan_route`, but one that cannot be reached
    /// is refused and the path there was (followed or not) is kept, as Nav2 keeps the
    /// goal it has when a new one is rejected.
    pub(super) fn new_goal(&mut self, target: Target) -> bool {
        let planned = self.plan_or(target, OnFailure::Keep);
        if planned {
            self.goal_replaces_route();
        }
        planned
    }

    fn plan_or(&mut self, target: Target, on_failure: OnFailure) -> bool {
        let label = target.label();
        let start = self.pose().position();
        let goal = match target {
            Target::Point(p) => p,
            Target::Pose(p) => p.position(),
            Target::Marker(id) => match self.marker_goal(id) {
                Some(p) => p,
                None => {
                    self.log(
                        Level::Error,
                        format!("no path to marker {id}: it is not on the map yet"),
                    );
                    self.refuse(&label, on_failure);
                    return false;
                }
            },
        };
        if let Some(n) = self.keepout_holding(goal) {
            self.log(
                Level::Error,
                format!("no path to {label}: it is inside keepout zone {n}"),
            );
            self.refuse(&label, on_failure);
            return false;
        }
        self.sync_keepout();
        let map = escape_map(
            self.belief.costmap(),
            start,
            self.settings.map.lethal_radius,
        );
        let began = self.stopwatch.as_ref().map(|w| w.now());
        let result = self
            .nav
            .planner
            .plan(&map, start, goal, &self.settings.plan);
        let took = began.zip(self.stopwatch.as_ref().map(|w| w.now()));
        match result {
            Ok(plan) => {
                let time = took.map_or(String::new(), |(a, b)| {
                    format!(", planned in {:.1} ms", (b - a) * 1e3)
                });
                self.log(
                    Level::Success,
                    format!(
                        "path to {label}: {:.2} m, cost {:.1}, {} waypoints{time}",
                        plan.length,
                        plan.cost,
                        plan.waypoints.len()
                    ),
                );
                // A new plan has not been driven: whatever "arrived" said was the old one's.
                self.nav.arrived = false;
                self.follower.set_goal_heading(target.heading());
                if self.mode == Mode::PathFollowing {
                    self.follower.set_trajectory(plan.trajectory.clone());
                }
                self.nav.route = Some(Route {
                    target,
                    goal,
                    label,
                    plan,
                });
                self.nav.checked_revision = self.belief.revision();
                // Only landmarks that turn up after this plan count as new near its path.
                self.nav.landmarks_checked = self.ekf.landmarks().map(|l| l.id).collect();
                true
            }
            Err(e) => {
                self.log(Level::Error, format!("no path to {label}: {e}"));
                self.refuse(&label, on_failure);
                false
            }
        }
    }

    /// After a failed plan: drops the old path, or says the goal was refused and the old
    /// one kept.
    fn refuse(&mut self, label: &str, on_failure: OnFailure) {
        let before = self.nav.route.as_ref().map(|r| r.label.clone());
        match (on_failure, before) {
            (OnFailure::Keep, Some(old)) => {
                let kept = if self.mode == Mode::PathFollowing && !self.nav.arrived {
                    format!("still following the path to {old}")
                } else {
                    format!("the path to {old} is kept")
                };
                self.log(Level::Warn, format!("goal {label} refused; {kept}"));
            }
            _ => self.drop_route(),
        }
    }

    /// Forgets the route; the robot stops if it was following it.
    pub(super) fn drop_route(&mut self) {
        self.nav.route = None;
        self.nav.following = None;
        self.nav.last_step = None;
        self.follower.clear_trajectory();
    }

    /// The approach point of landmark `id` as the map stands: seed 001's 12 cm for a block,
    /// otherwise just clear of the lethal ring.
    fn marker_goal(&self, id: u32) -> Option<Point2> {
        let landmark = self.ekf.landmark(id)?;
        let block = matches!(
            MarkerCategory::of(id),
            MarkerCategory::RedBlock | MarkerCategory::BlueBlock
        );
        let (approach, margin) = if block {
            (BLOCK_APPROACH, 0.0)
        } else {
            (0.0, APPROACH_MARGIN)
        };
        let from = self.pose().position();
        Some(approach_point(
            self.belief.costmap(),
            landmark.mean,
            from,
            approach,
            margin,
        ))
    }

    /// Starts following the route, planned afresh from where the robot is now.
    pub(super) fn start_following(&mut self) -> bool {
        let Some(route) = &self.nav.route else {
            self.log(
                Level::Warn,
                "no path to follow: plan one in thinking mode (t) or with :goto",
            );
            return false;
        };
        let (target, label) = (route.target, route.label.clone());
        // A path planned from where the robot stands, on the map as it is, is followed
        // as it is (a goal from RViz plans and starts at once); any other is planned again.
        let here = self.pose().position();
        let fresh = self.nav.checked_revision == self.belief.revision()
            && (route.plan.waypoints.first()).is_some_and(|p| p.distance(here) < 1e-6);
        self.nav.arrived = false;
        self.nav.true_cross_track = Rms::default();
        self.nav.cross_track = Rms::default();
        if !fresh && !self.plan_route(target) {
            return false;
        }
        if let Some(route) = &self.nav.route {
            self.follower.set_trajectory(route.plan.trajectory.clone());
        }
        self.log(
            Level::Info,
            format!(
                "following path to {label} with the {} controller",
                self.follower.controller().label()
            ),
        );
        true
    }

    /// The follower's command at `t`, replanning first if the map now blocks the path.
    pub(super) fn follow(&mut self, t: f64) -> Twist {
        let dt = match self.step_due(self.nav.last_step, t) {
            Ok(dt) => dt,
            Err(twist) => return twist,
        };
        self.replan_if_blocked(t);
        let step = self.follower.step(self.pose(), dt);
        let twist = self.guarded(t, step.twist);
        self.nav.last_step = Some((t, twist));
        match step.status {
            FollowStatus::Following {
                remaining,
                eta,
                cross_track,
            } => {
                self.nav.following = Some(FollowView {
                    remaining,
                    eta,
                    cross_track,
                });
                self.nav.cross_track.add(cross_track);
                self.sample_true_cross_track();
            }
            FollowStatus::Arrived => {
                if !self.nav.arrived {
                    self.nav.arrived = true;
                    self.nav.following = None;
                    let p = self.pose();
                    let route = self.nav.route.as_ref();
                    let label = route.map_or(String::new(), |r| r.label.clone());
                    let facing = match route.and_then(|r| r.target.heading()) {
                        Some(_) => format!(" facing {:.0}°", p.theta.to_degrees()),
                        None => String::new(),
                    };
                    self.log(
                        Level::Success,
                        format!(
                            "Destination arrived: {label} at ({:.2}, {:.2}){facing}",
                            p.x, p.y
                        ),
                    );
                    self.waypoint_arrived(t);
                }
            }
            FollowStatus::Turning { .. } | FollowStatus::NoTrajectory => self.nav.following = None,
        }
        twist
    }

    /// A goal from outside (RViz's "2D Goal Pose"): plan to it and drive there, as Nav2
    /// does with a goal; the robot ends facing the goal's heading.
    pub(super) fn drive_to_goal(&mut self, goal: Pose2) {
        let target = Target::Pose(goal);
        self.log(
            Level::Info,
            format!("goal pose received: {}", target.label()),
        );
        if self.mode == Mode::PathFollowing {
            // Following already: the new plan replaces the path being followed.
            if self.new_goal(target) {
                self.nav.true_cross_track = Rms::default();
                self.nav.cross_track = Rms::default();
            }
            return;
        }
        if self.new_goal(target) {
            self.set_mode(Mode::PathFollowing);
        }
    }

    /// Seed 001 section 7 "Path Recalculation": replan when the map shows the path ahead
    /// blocked, or a new obstacle appears within 1 m of it, or a new block within 0.5 m.
    fn replan_if_blocked(&mut self, t: f64) {
        if t - self.nav.last_replan < REPLAN_EVERY {
            return;
        }
        let Some(route) = &self.nav.route else { return };
        let from = self.follower.progress().map_or(0, |p| p.index);
        let points = &route.plan.trajectory.points;
        let ahead = &points[from.min(points.len())..];
        let mut reason: Option<String> = None;
        let revision = self.belief.revision();
        if revision != self.nav.checked_revision {
            self.nav.checked_revision = revision;
            let map = self.belief.costmap();
            // Where the footprint stands now is no block to the path: what the lidar mapped
            // under it (a block just picked up, its face mapped a few centimetres towards the
            // robot) is the robot's own place, as Nav2's footprint clearing treats it.
            let (robot, body) = (self.pose().position(), self.settings.robot.footprint_radius);
            let beyond = |p: Point2| p.distance(robot) > body;
            if let Some(p) =
                (ahead.iter()).find(|p| beyond(p.position) && is_lethal(map.at(p.position)))
            {
                let at = p.position;
                reason = Some(format!("path blocked at ({:.2}, {:.2})", at.x, at.y));
            }
        }
        for landmark in self.ekf.landmarks() {
            if !self.nav.landmarks_checked.insert(landmark.id) || reason.is_some() {
                continue;
            }
            let category = MarkerCategory::of(landmark.id);
            let near = match category {
                MarkerCategory::Obstacle => NEW_OBSTACLE_NEAR,
                MarkerCategory::RedBlock | MarkerCategory::BlueBlock => NEW_BLOCK_NEAR,
                _ => continue,
            };
            if ahead
                .iter()
                .any(|p| p.position.distance(landmark.mean) < near)
            {
                reason = Some(format!(
                    "new {} {} within {near} m of the path",
                    category.label(),
                    landmark.id
                ));
            }
        }
        let Some(reason) = reason else { return };
        self.replan(t, reason);
    }

    /// Plans the route again from where the robot is, saying why first.
    pub(super) fn replan(&mut self, t: f64, reason: String) {
        let Some(route) = &self.nav.route else { return };
        let target = route.target;
        self.nav.last_replan = t;
        self.nav.replans += 1;
        self.log(Level::Warn, format!("{reason}: replanning"));
        if self.plan_route(target) {
            self.follower.set_trajectory(
                self.nav
                    .route
                    .as_ref()
                    .map(|r| r.plan.trajectory.clone())
                    .unwrap_or_default(),
            );
        }
    }

    pub(super) fn set_controller(&mut self, kind: navdeck_core::control::config::ControllerKind) {
        self.follower.set_controller(kind);
        self.nav.last_step = None;
        self.log(Level::Info, format!("path controller: {}", kind.label()));
    }
}
