//! Waypoint following as Nav2's rviz panel has it ("Waypoint / Nav Through Poses mode"):
//! goals queued in order, started, paused, skipped, looped N times and cleared. Each
//! waypoint is reached by the same planner and follower as a single goal; when the
//! follower arrives, the next waypoint is planned and followed at once.

pub mod file;

use super::Pilot;
use super::mode::Mode;
use super::navigation::Target;
use navdeck_core::data::Level;
use navdeck_core::geometry::{Point2, Pose2};

/// One goal of a route: a position in the map frame, and the heading to end with if any.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Waypoint {
    pub position: Point2,
    /// Radians (REP-103); `None` ends facing whichever way the path arrives.
    pub yaw: Option<f64>,
}

impl Waypoint {
    /// The goal the planner is given for it.
    pub fn target(self) -> Target {
        match self.yaw {
            Some(yaw) => Target::Pose(Pose2::new(self.position.x, self.position.y, yaw)),
            None => Target::Point(self.position),
        }
    }
}

/// A waypoint reached: which one, in which loop, when, and where the robot was.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Arrival {
    /// 0-based index in the route.
    pub index: usize,
    /// 0-based loop.
    pub lap: usize,
    pub time: f64,
    pub estimate: Pose2,
    /// The twin's true pose, when the link has one (for scoring only).
    pub truth: Option<Pose2>,
}

/// What the user can ask of the route (`:waypoint …`, `:route …`, the thinking key).
#[derive(Clone, Debug, PartialEq)]
pub enum RouteAsk {
    /// Queue a waypoint at the end.
    Add(Waypoint),
    /// Start (or resume) following the waypoints in order.
    Start,
    /// Stop where the robot stands; start resumes at the same waypoint.
    Pause,
    /// Give up the current waypoint and go on to the next.
    Skip,
    /// Drive the whole route this many times.
    Loop(usize),
    /// Forget every waypoint.
    Clear,
    /// Replace the waypoints (a route file), with its loop count.
    Load {
        waypoints: Vec<Waypoint>,
        loops: usize,
    },
}

/// The queued waypoints and how far along them the robot is.
#[derive(Clone, Debug)]
pub struct Waypoints {
    goals: Vec<Waypoint>,
    /// The waypoint being driven to (0-based); `goals.len()` when the route is done.
    current: usize,
    /// Times the route is driven, at least 1, and the loop under way (0-based).
    loops: usize,
    lap: usize,
    /// Started and not finished, cleared or replaced by another goal.
    active: bool,
    arrivals: Vec<Arrival>,
}

impl Default for Waypoints {
    fn default() -> Self {
        Self {
            goals: Vec::new(),
            current: 0,
            loops: 1,
            lap: 0,
            active: false,
            arrivals: Vec::new(),
        }
    }
}

impl Waypoints {
    pub fn goals(&self) -> &[Waypoint] {
        &self.goals
    }
    /// The waypoint being driven to, 0-based, while the route runs.
    pub fn current(&self) -> Option<usize> {
        (self.active && self.current < self.goals.len()).then_some(self.current)
    }
    pub fn loops(&self) -> usize {
        self.loops
    }
    /// The loop under way, 0-based.
    pub fn lap(&self) -> usize {
        self.lap
    }
    pub fn is_active(&self) -> bool {
        self.active
    }
    /// Every waypoint reached since the route was last started from its beginning.
    pub fn arrivals(&self) -> &[Arrival] {
        &self.arrivals
    }
    /// "waypoint 3/5, loop 1/2" while the route runs; "5 waypoints" when it does not.
    pub fn progress(&self) -> Option<String> {
        let n = self.goals.len();
        if n == 0 {
            return None;
        }
        let loops = match self.loops {
            1 => String::new(),
            l => format!(", loop {}/{l}", (self.lap + 1).min(l)),
        };
        let plural = if n == 1 { "" } else { "s" };
        Some(if self.active {
            format!("waypoint {}/{n}{loops}", (self.current + 1).min(n))
        } else if self.current >= n {
            format!("{n} waypoint{plural} done")
        } else if self.current == 0 && self.lap == 0 {
            match self.loops {
                1 => format!("{n} waypoint{plural}"),
                l => format!("{n} waypoint{plural} x{l} loops"),
            }
        } else {
            format!("stopped at {}/{n}{loops}", self.current + 1)
        })
    }

    /// Moves on past the current waypoint; false when the route is done.
    fn advance(&mut self) -> bool {
        self.current += 1;
        if self.current < self.goals.len() {
            return true;
        }
        if self.lap + 1 < self.loops {
            self.lap += 1;
            self.current = 0;
            return true;
        }
        self.active = false;
        false
    }
}

impl Pilot {
    /// Applies a route request; true when the robot's motion changed.
    pub(super) fn ask_route(&mut self, ask: RouteAsk) -> bool {
        match ask {
            RouteAsk::Add(w) => {
                self.nav.waypoints.goals.push(w);
                let n = self.nav.waypoints.goals.len();
                self.log(
                    Level::Info,
                    format!(
                        "waypoint {n} added: {} (:route start drives them)",
                        w.target().label()
                    ),
                );
                false
            }
            RouteAsk::Start => self.start_waypoints(),
            RouteAsk::Pause => {
                if !self.nav.waypoints.active || self.mode != Mode::PathFollowing {
                    self.log(Level::Info, "route not running: nothing to pause");
                    return false;
                }
                self.set_mode(Mode::Manual);
                let at = self.nav.waypoints.current + 1;
                self.log(
                    Level::Info,
                    format!("route paused before waypoint {at} (:route start resumes)"),
                );
                true
            }
            RouteAsk::Skip => {
                let w = &mut self.nav.waypoints;
                if !w.active {
                    self.log(Level::Warn, "route not running: :route start first");
                    return false;
                }
                let skipped = w.current + 1;
                self.log(Level::Info, format!("waypoint {skipped} skipped"));
                self.next_waypoint()
            }
            RouteAsk::Loop(n) => {
                self.nav.waypoints.loops = n.max(1);
                self.nav.waypoints.lap = self.nav.waypoints.lap.min(n.max(1) - 1);
                self.log(Level::Info, format!("route loops {} times", n.max(1)));
                false
            }
            RouteAsk::Clear => {
                let was_running = self.nav.waypoints.active && self.mode == Mode::PathFollowing;
                self.nav.waypoints = Waypoints::default();
                self.log(Level::Info, "route cleared");
                if was_running {
                    self.drop_route();
                    self.set_mode(Mode::Manual);
                }
                was_running
            }
            RouteAsk::Load { waypoints, loops } => {
                let n = waypoints.len();
                self.nav.waypoints = Waypoints {
                    goals: waypoints,
                    loops: loops.max(1),
                    ..Waypoints::default()
                };
                self.log(
                    Level::Info,
                    format!(
                        "route of {n} waypoints, {} loop(s) (:route start drives it)",
                        loops.max(1)
                    ),
                );
                false
            }
        }
    }

    /// Starts the route, or resumes it at the waypoint it stopped before.
    fn start_waypoints(&mut self) -> bool {
        let w = &mut self.nav.waypoints;
        if w.goals.is_empty() {
            self.log(
                Level::Warn,
                "no waypoints: add them with :waypoint add X Y [THETA_DEG] or a in thinking mode",
            );
            return false;
        }
        if w.current >= w.goals.len() || (!w.active && w.current == 0 && w.lap == 0) {
            w.current = 0;
            w.lap = 0;
            w.arrivals.clear();
        }
        w.active = true;
        self.drive_to_waypoint()
    }

    /// Plans to the current waypoint and follows the path.
    fn drive_to_waypoint(&mut self) -> bool {
        let w = &self.nav.waypoints;
        let Some(goal) = w.goals.get(w.current).copied() else {
            return false;
        };
        let progress = w.progress().unwrap_or_default();
        self.log(Level::Info, format!("route: {progress}"));
        if !self.plan_route(goal.target()) {
            // Nothing to follow: the route waits here until skipped or started again.
            self.nav.waypoints.active = false;
            self.set_mode(Mode::Manual);
            return true;
        }
        if self.mode == Mode::PathFollowing {
            return true;
        }
        self.set_mode(Mode::PathFollowing)
    }

    /// On to the next waypoint (or the route's end).
    fn next_waypoint(&mut self) -> bool {
        if self.nav.waypoints.advance() {
            return self.drive_to_waypoint();
        }
        let w = &self.nav.waypoints;
        let (n, loops) = (w.goals.len(), w.loops);
        self.log(
            Level::Success,
            format!("route done: {n} waypoints, {loops} loop(s)"),
        );
        false
    }

    /// The follower arrived: if it was at the route's current waypoint, note it and go on.
    pub(super) fn waypoint_arrived(&mut self, t: f64) {
        let w = &self.nav.waypoints;
        let Some(index) = w.current() else { return };
        let target = w.goals[index].target();
        if self.nav.route.as_ref().map(|r| r.target) != Some(target) {
            return;
        }
        let arrival = Arrival {
            index,
            lap: w.lap,
            time: t,
            estimate: self.pose(),
            truth: self.estimating.truth,
        };
        let (n, lap, loops) = (w.goals.len(), w.lap, w.loops);
        self.nav.waypoints.arrivals.push(arrival);
        self.log(
            Level::Success,
            format!(
                "waypoint {}/{n} reached, loop {}/{loops}",
                index + 1,
                lap + 1
            ),
        );
        self.next_waypoint();
    }

    /// A goal of its own replaces the route, as a new goal cancels Nav2's waypoint following.
    pub(super) fn goal_replaces_route(&mut self) {
        if self.nav.waypoints.active {
            self.nav.waypoints.active = false;
            self.log(
                Level::Info,
                "route stopped: the new goal replaces it (:route start resumes)",
            );
        }
    }

    /// The queued waypoints and the progress along them.
    pub fn waypoints(&self) -> &Waypoints {
        &self.nav.waypoints
    }
}
