//! The pilot: everything that decides how the robot moves, free of terminal, clock and
//! link. Odometry and EKF-SLAM, the planning map, the planner and path follower, keyboard
//! driving with its deadman, the mission, navigation, and the safety gate (e-stop, link
//! in doubt) all live here.
//!
//! One entry point, in the shape of the mission's step: `step(Input) -> Output`. The
//! input is the time, what the user asked (an `Intent`), what the link reported and
//! whether a command is due; the output is the command to send and the log lines.
//! The console (`app/`) owns the link and the screen and calls `step`; the headless
//! mission runner calls it directly.

pub mod arm;
pub mod behaviours;
pub mod config;
mod control;
pub mod estimate;
mod exploration;
mod intent;
pub mod lane;
pub mod lidar_slam;
pub mod localize;
mod map_load;
mod mapping;
pub mod mode;
pub mod navigation;
mod reckoning;
mod safety;
mod step;
pub mod tag_route;
mod tag_route_drive;
pub mod teleop;
mod trail;
pub mod waypoints;
pub mod zones;

use config::Settings;
use mode::Mode;
use nalgebra::Matrix3;
use navdeck_core::clock::Clock;
use navdeck_core::data::{Command, GripperCommand, GripperState, LaserScan, Level, SensorFrame};
use navdeck_core::geometry::{Point2, Pose2, Twist};
use navdeck_core::map::belief::BeliefMap;
use navdeck_core::slam::ekf::EkfSlam;
use navdeck_core::slam::odometry::Odometry;
use std::sync::Arc;
use teleop::{DriveKey, Teleop};

pub use intent::Intent;
pub use safety::LinkStatus;
pub use step::{Due, Input, Robot};

/// One log line of the pilot's.
#[derive(Clone, Debug, PartialEq)]
pub struct LogLine {
    pub time: f64,
    pub level: Level,
    pub text: String,
}

/// One step's output.
#[derive(Debug, Default)]
pub struct Output {
    /// The command sent, when one was due.
    pub command: Option<Command>,
    /// What the robot reported, when it was polled.
    pub frame: Option<SensorFrame>,
    /// Why polling the robot failed, when it did.
    pub failure: Option<String>,
    pub log: Vec<LogLine>,
}

/// The gripper as last reported, the command waiting for the next send, and the arm
/// that carries it when the config has one.
#[derive(Clone, Debug, Default)]
struct Hand {
    state: Option<GripperState>,
    pending: Option<GripperCommand>,
    arm: Option<arm::ArmPilot>,
}

/// The autonomy core; see the module comment.
pub struct Pilot {
    settings: Settings,
    now: f64,
    mode: Mode,
    teleop: Teleop,
    odometry: Odometry,
    ekf: EkfSlam,
    /// The lidar estimator, when one runs: MCL on a known map, or lidar SLAM.
    scan_estimator: localize::ScanEstimator,
    estimating: estimate::Estimating,
    /// The planning map the robot builds from what it senses.
    belief: BeliefMap,
    upkeep: mapping::Upkeep,
    follower: navdeck_core::control::follower::Follower,
    nav: navigation::Navigation,
    exploring: exploration::Exploring,
    /// The arbiter, and the gate its e-stop reads.
    behaviours: behaviours::Behaviours,
    measuring: control::Measuring,
    hand: Hand,
    /// Lane mode: the lane driver and the newest lane sighting.
    lane: lane::Lane,
    /// Route mode (seed 003): the tag map, the run, the tags seen.
    tag_route: tag_route::TagRouting,
    /// A monotonic clock, installed by the runner, to time planning for the log only.
    stopwatch: Option<Arc<dyn Clock>>,
    log: Vec<LogLine>,
}

impl Pilot {
    /// A pilot starting at `start` at session time `now`, with a planning map of at least
    /// `extent` (width, height) metres.
    pub fn new(settings: Settings, start: Pose2, extent: (f64, f64), now: f64) -> Self {
        let (robot, teleop) = (&settings.robot, &settings.teleop);
        let teleop = Teleop::new(
            teleop,
            teleop.max_linear.min(robot.max_linear),
            teleop.max_angular.min(robot.max_angular),
        );
        let m = &settings.map;
        let mut pilot = Self {
            now,
            mode: Mode::Manual,
            teleop,
            odometry: Odometry::new(start, robot.track),
            // The map frame starts at the robot: its pose is known exactly there.
            ekf: EkfSlam::new(start, Matrix3::zeros(), &settings.slam, robot.track),
            scan_estimator: localize::ScanEstimator::for_settings(&settings, start),
            estimating: estimate::Estimating::default(),
            belief: BeliefMap::new(m, (m.width.max(extent.0), m.height.max(extent.1))),
            upkeep: mapping::Upkeep::default(),
            follower: navdeck_core::control::follower::Follower::new(
                settings.follow.clone(),
                settings.plan.max_speed.min(robot.max_linear),
                robot.max_angular,
            ),
            nav: navigation::Navigation::default(),
            exploring: exploration::Exploring::default(),
            behaviours: behaviours::Behaviours::new(&settings),
            measuring: control::Measuring::default(),
            hand: Hand {
                arm: settings.arm.clone().map(arm::ArmPilot::new),
                ..Hand::default()
            },
            lane: lane::Lane::new(settings.lane.clone()),
            tag_route: tag_route::TagRouting::default(),
            stopwatch: None,
            log: Vec::new(),
            settings,
        };
        pilot.map_footprint();
        pilot
    }

    /// Installs the clock that times planning (seconds, monotonic), for the log only.
    pub fn set_stopwatch(&mut self, stopwatch: Arc<dyn Clock>) {
        self.stopwatch = Some(stopwatch);
    }

    fn log(&mut self, level: Level, text: impl Into<String>) {
        self.log_at(self.now, level, text);
    }

    fn log_at(&mut self, time: f64, level: Level, text: impl Into<String>) {
        self.log.push(LogLine {
            time,
            level,
            text: text.into(),
        });
    }

    // ----- read-only views for the console, the runners and the tests -----

    pub fn settings(&self) -> &Settings {
        &self.settings
    }
    pub fn mode(&self) -> Mode {
        self.mode
    }
    pub fn teleop(&self) -> &Teleop {
        &self.teleop
    }
    pub fn estimated_pose(&self) -> Pose2 {
        self.pose()
    }
    /// Where wheel odometry alone puts the robot (dead reckoning).
    pub fn odometry_pose(&self) -> Pose2 {
        self.odometry.pose()
    }
    pub fn odometry_distance(&self) -> f64 {
        self.odometry.distance()
    }
    pub fn commanded(&self) -> Twist {
        self.measuring.commanded
    }
    pub fn measured(&self) -> Twist {
        self.measuring.measured
    }
    pub fn gripper(&self) -> Option<GripperState> {
        self.hand.state
    }
    pub fn estop(&self) -> bool {
        self.behaviours.gate.estop
    }
    /// The collision monitor's zones (`[safety]`), robot frame.
    pub fn collision_zones(&self) -> &[navdeck_core::control::collision_monitor::zone::Zone] {
        self.behaviours.collision.monitor.zones()
    }
    /// Each sensor's health: which are lost now, and the outages so far.
    pub fn sensor_health(&self) -> &navdeck_core::health::SensorHealth {
        &self.behaviours.health
    }
    /// The arbiter: which behaviour's command goes out, and the transitions.
    pub fn arbiter(&self) -> &behaviours::Arbiter {
        &self.behaviours.arbiter
    }
    pub fn link_status(&self) -> &LinkStatus {
        &self.behaviours.gate.link
    }
    /// Whether the robot has answered at least once this session: until it has, a link
    /// that is not answering is still being waited for, not lost.
    pub fn link_ever_up(&self) -> bool {
        self.behaviours.gate.link_was_up
    }
    pub fn slam(&self) -> &EkfSlam {
        &self.ekf
    }
    /// The robot's planning map.
    pub fn belief(&self) -> &BeliefMap {
        &self.belief
    }
    /// The newest lidar scan and the estimated pose it was taken from.
    pub fn newest_scan(&self) -> Option<(Pose2, &LaserScan)> {
        self.upkeep.newest_scan.as_ref().map(|(p, s)| (*p, s))
    }
    /// Where the robot has driven (estimated positions, oldest first).
    pub fn trail(&self) -> &[Point2] {
        self.upkeep.trail.points()
    }
    /// Drive keys still held at `now`, for the status panel.
    pub fn held_keys(&self, now: f64) -> Vec<DriveKey> {
        self.teleop.clone().held_at(now, self.brake_margin())
    }
    /// Where a new goal cursor starts: the route's goal, else the robot.
    pub fn cursor_start(&self) -> Point2 {
        self.nav
            .route
            .as_ref()
            .map_or(self.pose().position(), |r| r.goal)
    }
}
