//! The console's state and behaviour, free of terminal and clock: actions in, commands out.
//!
//! Time is passed in as `now` (seconds on the session clock): the TUI passes wall time,
//! the headless runner and the tests pass simulated time.

pub mod action;
mod camera_feed;
mod command;
mod control;
pub mod estimate;
mod exploration;
pub mod loading;
pub mod log;
mod mapping;
pub mod mode;
pub mod navigation;
mod picture;
mod revision;
mod saving;
pub mod screen;
pub mod teleop;
pub mod view;

use crate::config::Config;
use crate::data::{GripperCommand, GripperState, MarkerSighting};
use crate::geometry::{Point2, Pose2, Twist};
use crate::keymap::{Key, KeyCode, Keymap};
use crate::link::RobotLink;
use crate::map::belief::BeliefMap;
use crate::map::grid::OccupancyGrid;
use crate::slam::ekf::EkfSlam;
use crate::slam::odometry::Odometry;
use action::Action;
use command::Intent;
use log::{Level, LogBook};
use mode::Mode;
use nalgebra::Matrix3;
use teleop::Teleop;
use view::ViewState;

/// What a key event was: terminals without the kitty protocol only ever report `Press`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum KeyKind {
    Press,
    Repeat,
    Release,
}

/// Whether the robot link is answering.
#[derive(Clone, Debug, PartialEq)]
pub enum LinkStatus {
    Ok,
    Lost(String),
    /// Data flows again, but the robot stays still until the user presses a key.
    Back,
}

/// How long a marker stays marked "in view" after its last sighting, seconds.
pub const IN_VIEW_HOLD: f64 = 0.5;

/// Resolution of the world raster drawn on the map, metres.
pub const WORLD_RASTER: f64 = 0.02;

/// Everything the console knows, and the only place actions change it.
pub struct App {
    config: Config,
    keymap: Keymap,
    link: Box<dyn RobotLink>,
    mode: Mode,
    teleop: Teleop,
    odometry: Odometry,
    ekf: EkfSlam,
    accuracy: estimate::Accuracy,
    /// Camera frames seen, for race mode's every-k-th correction.
    camera_frames: u64,
    race_sigma_warned: bool,
    manual_speeds: (f64, f64),
    log: LogBook,
    view: ViewState,
    /// Terminal size in cells, as last reported.
    screen: (u16, u16),
    now: f64,
    clock: control::ControlClock,
    commanded: Twist,
    measured: Twist,
    gripper: Option<GripperState>,
    pending_gripper: Option<GripperCommand>,
    estop: bool,
    quit: bool,
    /// Marker IDs and when each was last seen: the map marks them "in view" for a while.
    in_view: Vec<(u32, f64)>,
    link_status: LinkStatus,
    /// Whether the link has ever answered: only a loss after that needs a key to resume.
    link_was_up: bool,
    collisions_logged: u32,
    world_grid: Option<OccupancyGrid>,
    /// The planning map the robot builds from what it senses.
    belief: BeliefMap,
    last_footprint: Option<Point2>,
    /// Where and when the last scan was folded into the map.
    last_scan_pose: Option<(Pose2, f64)>,
    /// The map revision on screen and the session second it was taken in.
    map_shown: (u64, f64),
    planner: crate::plan::pipeline::Planner,
    follower: crate::control::follower::Follower,
    nav: navigation::Navigation,
    exploring: exploration::Exploring,
    /// Marker IDs the filter must not correct with: blocks the mission moved.
    ignored_markers: Vec<u32>,
    /// Where maps are saved, how they are dated, and when exploration last saved one.
    maps_dir: Option<std::path::PathBuf>,
    date_source: Option<Box<dyn Fn() -> String + Send>>,
    last_autosave: f64,
    picker: loading::Picker,
    /// A monotonic clock in seconds, installed by the runner, to time planning; the
    /// console itself never reads a clock.
    stopwatch: Option<std::sync::Arc<dyn crate::clock::Clock>>,
    revision: u64,
    visible: Option<revision::Visible>,
    /// When the full picture last went to the link, and the map revision it carried.
    picture_at: f64,
    picture_map: Option<u64>,
    camera: camera_feed::CameraFeed,
}

impl App {
    /// A console on `link`, starting at session time `now`.
    pub fn new(config: Config, keymap: Keymap, link: Box<dyn RobotLink>, now: f64) -> Self {
        let start = link.ground_truth().map_or(Pose2::default(), |t| t.pose());
        let world_grid = link
            .ground_truth()
            .map(|t| t.world().rasterize(WORLD_RASTER));
        let belief = mapping::belief_map_for(&config, link.as_ref());
        let teleop = Teleop::new(
            &config.teleop,
            config.teleop.max_linear.min(config.robot.max_linear),
            config.teleop.max_angular.min(config.robot.max_angular),
        );
        let mut app = Self {
            odometry: Odometry::new(start, config.robot.track),
            // The map frame starts at the robot: its pose is known exactly there.
            ekf: EkfSlam::new(start, Matrix3::zeros(), &config.slam, config.robot.track),
            accuracy: estimate::Accuracy::default(),
            camera_frames: 0,
            race_sigma_warned: false,
            manual_speeds: (0.0, 0.0),
            clock: control::ControlClock::new(now, config.robot.control_period),
            teleop,
            keymap,
            link,
            mode: Mode::Manual,
            log: LogBook::new(500),
            view: ViewState::default(),
            screen: (80, 24),
            now,
            commanded: Twist::ZERO,
            measured: Twist::ZERO,
            gripper: None,
            pending_gripper: None,
            estop: false,
            quit: false,
            in_view: Vec::new(),
            link_status: LinkStatus::Ok,
            link_was_up: false,
            collisions_logged: 0,
            world_grid,
            belief,
            last_footprint: None,
            last_scan_pose: None,
            map_shown: (0, f64::NEG_INFINITY),
            planner: crate::plan::pipeline::Planner::new(),
            follower: crate::control::follower::Follower::new(
                config.follow.clone(),
                config.plan.max_speed.min(config.robot.max_linear),
                config.robot.max_angular,
            ),
            nav: navigation::Navigation::default(),
            exploring: exploration::Exploring::default(),
            ignored_markers: Vec::new(),
            maps_dir: None,
            date_source: None,
            last_autosave: now,
            picker: loading::Picker::default(),
            stopwatch: None,
            revision: 0,
            visible: None,
            picture_at: f64::NEG_INFINITY,
            picture_map: None,
            camera: camera_feed::CameraFeed::default(),
            config,
        };
        app.map_footprint();
        let label = app.link.label();
        app.log(
            Level::Info,
            format!("navdeck {} on {label}", env!("CARGO_PKG_VERSION")),
        );
        app.log(
            Level::Info,
            format!("keymap {}; press ? for help", app.keymap.source()),
        );
        app
    }

    fn log(&mut self, level: Level, text: impl Into<String>) {
        self.log.push(self.now, level, text);
    }

    /// Resolves a key through the active mode's keymap and acts on it.
    pub fn handle_key(&mut self, key: Key, kind: KeyKind, now: f64) {
        self.advance_to(now);
        if kind == KeyKind::Press && self.link_status == LinkStatus::Back {
            // Control resumes only on the user's word after a loss (the key is not acted on).
            self.link_status = LinkStatus::Ok;
            self.log(Level::Success, "control resumed");
            self.refresh_revision();
            return;
        }
        if kind == KeyKind::Release {
            // Only terminals speaking the kitty protocol send releases.
            self.teleop.set_release_events(true);
        }
        if self.nav.prompt.is_some() {
            if kind != KeyKind::Release {
                self.edit_prompt(key);
            }
            return;
        }
        let action = self.keymap.lookup(self.mode, key).or_else(|| {
            // In the autonomous modes the manual drive keys take control back.
            self.keymap
                .lookup(Mode::Manual, key)
                .filter(|a| a.motion().is_some() && !self.mode.drives_by_keys())
        });
        let Some(action) = action else {
            if kind == KeyKind::Press && self.view.help {
                // Any unbound key closes the help overlay.
                self.view.help = false;
            }
            return;
        };
        match kind {
            KeyKind::Release => {
                if action.motion().is_some() {
                    self.teleop.release(action);
                    self.control_step(self.now);
                }
            }
            KeyKind::Press | KeyKind::Repeat => {
                if action.motion().is_some() {
                    self.drive_key(action, kind == KeyKind::Repeat);
                } else if kind == KeyKind::Press {
                    self.apply(action);
                }
            }
        }
    }

    /// Keys typed after `:`: enter runs the command, esc (or backspace on empty) cancels.
    fn edit_prompt(&mut self, key: Key) {
        let Some(text) = self.nav.prompt.as_mut() else {
            return;
        };
        match key.code {
            KeyCode::Enter => {
                let line = self.nav.prompt.take().unwrap_or_default();
                self.run_command(line.trim());
            }
            KeyCode::Esc => self.nav.prompt = None,
            // Backspace deletes a character; on an empty line it closes the prompt, as in vim.
            KeyCode::Backspace if text.pop().is_none() => self.nav.prompt = None,
            KeyCode::Char(c) if !key.ctrl && !key.alt => text.push(c),
            KeyCode::Char('c') if key.ctrl => self.nav.prompt = None,
            _ => {}
        }
        self.refresh_revision();
    }

    fn drive_key(&mut self, action: Action, repeat: bool) {
        if !self.mode.drives_by_keys() {
            // A drive key in an autonomous mode takes control back at once.
            self.log(
                Level::Warn,
                format!(
                    "{} key: manual control taken back from {} mode",
                    action.name(),
                    self.mode.label().to_lowercase()
                ),
            );
            self.set_mode(Mode::Manual);
        }
        if self.estop {
            self.estop = false;
            self.log(Level::Info, "emergency stop released by a drive key");
        }
        self.teleop.press(action, self.now, repeat);
        // Act on the key now rather than at the next tick: a tap moves at once.
        self.control_step(self.now);
    }

    /// The one place the console's state changes: a key's action or a typed command.
    pub fn apply(&mut self, intent: impl Into<Intent>) {
        let action = match intent.into() {
            Intent::Action(action) => action,
            Intent::Typed(typed) => return self.apply_typed(typed),
        };
        match action {
            Action::ModeManual => self.set_mode(Mode::Manual),
            Action::ModeExplore => self.set_mode(Mode::Exploration),
            Action::ModeThink => self.set_mode(Mode::Thinking),
            Action::ModeFollow => self.set_mode(Mode::PathFollowing),
            Action::ModeRace => self.set_mode(Mode::Race),
            Action::ModeLoad => self.set_mode(Mode::Load),
            Action::GripperOpen => self.gripper_command(GripperCommand::Open),
            Action::GripperClose => self.gripper_command(GripperCommand::Close),
            Action::Quit => {
                self.shutdown("quit by user");
                self.quit = true;
            }
            Action::Stop => {
                self.teleop.clear();
                self.control_step(self.now);
                self.log(Level::Info, "stop");
            }
            Action::EmergencyStop => self.emergency_stop(),
            Action::SpeedUp
            | Action::SpeedDown
            | Action::LinearUp
            | Action::LinearDown
            | Action::AngularUp
            | Action::AngularDown => {
                if self.teleop.adjust(action) {
                    let (v, w) = (self.teleop.linear_speed, self.teleop.angular_speed);
                    self.log(Level::Info, format!("speed {v:.2} m/s, turn {w:.2} rad/s"));
                } else {
                    self.log(Level::Warn, "speeds already at their limit");
                }
            }
            Action::Help => self.view.help = !self.view.help,
            Action::ZoomIn | Action::ZoomOut => {
                let fitted = self.fitted_scale();
                self.view.zoom_step(fitted, action == Action::ZoomIn);
            }
            Action::PanLeft | Action::PanRight | Action::PanUp | Action::PanDown => {
                let (dx, dy) = match action {
                    Action::PanLeft => (-1.0, 0.0),
                    Action::PanRight => (1.0, 0.0),
                    Action::PanUp => (0.0, 1.0),
                    _ => (0.0, -1.0),
                };
                let from = self.map_center();
                let span = self.map_span();
                self.view.pan(from, span, dx, dy);
            }
            Action::CenterView => {
                self.view.center = None;
                self.view.zoom = None;
            }
            Action::ToggleBraille => self.view.braille = !self.view.braille,
            Action::ToggleLandmarks => self.view.landmarks = !self.view.landmarks,
            Action::ToggleCamera => self.view.camera = self.view.camera.next(),
            Action::ToggleTruth => {
                if self.link.ground_truth().is_some() {
                    self.view.show_truth = !self.view.show_truth;
                } else {
                    self.log(Level::Warn, "true pose exists only in the twin");
                }
            }
            Action::Forward
            | Action::Backward
            | Action::TurnLeft
            | Action::TurnRight
            | Action::ForwardLeft
            | Action::ForwardRight
            | Action::BackwardLeft
            | Action::BackwardRight => self.drive_key(action, false),
            Action::CursorUp if self.mode == Mode::Load => self.pick(-1),
            Action::CursorDown if self.mode == Mode::Load => self.pick(1),
            Action::PlanToCursor if self.mode == Mode::Load => self.load_selected(),
            Action::CursorLeft => self.move_cursor(-1.0, 0.0),
            Action::CursorRight => self.move_cursor(1.0, 0.0),
            Action::CursorUp => self.move_cursor(0.0, 1.0),
            Action::CursorDown => self.move_cursor(0.0, -1.0),
            Action::PlanToCursor => self.plan_to_cursor(),
            Action::CommandLine => self.nav.prompt = Some(String::new()),
            Action::ClearRoute => {
                self.drop_route();
                self.control_step(self.now);
                self.log(Level::Info, "path cleared");
            }
            Action::SaveMap => {
                self.save_map(saving::SAVE_KEY_NAME);
            }
            Action::NextController => {
                let all = crate::control::config::ControllerKind::ALL;
                let k = all
                    .iter()
                    .position(|&k| k == self.follower.controller())
                    .unwrap_or(0);
                self.set_controller(all[(k + 1) % all.len()]);
            }
            Action::Unbound => {}
        }
    }

    fn set_mode(&mut self, mode: Mode) {
        if !mode.is_built() {
            self.log(
                Level::Warn,
                format!("{} mode is not built yet", mode.label().to_lowercase()),
            );
            return;
        }
        if mode == self.mode {
            return;
        }
        if mode == Mode::PathFollowing && !self.start_following() {
            return;
        }
        self.teleop.clear();
        self.set_speed_limits(mode);
        if matches!(self.mode, Mode::PathFollowing | Mode::Exploration) {
            // Leaving an autonomous mode stops it at once.
            self.leave_autonomy();
        }
        self.nav.cursor = (mode == Mode::Thinking).then(|| {
            self.nav
                .route
                .as_ref()
                .map_or(self.ekf.pose().position(), |r| r.goal)
        });
        self.mode = mode;
        self.log(Level::Info, format!("mode {}", mode.label()));
        if mode == Mode::Exploration {
            self.start_mission();
        }
        if mode == Mode::Load {
            self.open_picker();
        }
        self.control_step(self.now);
    }

    /// Race mode drives up to the robot's limits; manual stays within teleop's.
    fn set_speed_limits(&mut self, mode: Mode) {
        let (c, r) = (&self.config, &self.config.robot);
        if mode == Mode::Race {
            self.manual_speeds = (self.teleop.linear_speed, self.teleop.angular_speed);
            let speeds = (c.race.linear_speed, c.race.angular_speed);
            self.teleop.set_limits(r.max_linear, r.max_angular, speeds);
        } else if self.mode == Mode::Race {
            let (lin, ang) = (
                c.teleop.max_linear.min(r.max_linear),
                c.teleop.max_angular.min(r.max_angular),
            );
            self.teleop.set_limits(lin, ang, self.manual_speeds);
        }
    }

    fn gripper_command(&mut self, cmd: GripperCommand) {
        if self.mode == Mode::Exploration && self.mission().is_some_and(|m| m.holds_gripper()) {
            self.log(
                Level::Warn,
                "gripper key ignored: the mission is using the gripper (m takes control)",
            );
            return;
        }
        self.pending_gripper = Some(cmd);
        let verb = match cmd {
            GripperCommand::Open => "opening",
            GripperCommand::Close => "closing",
        };
        self.log(Level::Info, format!("{verb} gripper"));
        self.control_step(self.now);
    }

    fn emergency_stop(&mut self) {
        self.teleop.clear();
        self.estop = true;
        if self.mode != Mode::Manual {
            self.set_speed_limits(Mode::Manual);
            self.mode = Mode::Manual;
            self.leave_autonomy();
            self.nav.cursor = None;
        }
        self.control_step(self.now);
        self.log(
            Level::Error,
            "EMERGENCY STOP: robot halted; drive keys release it",
        );
    }

    /// Stops following and the mission's driving at once: the trajectory and the last
    /// commands of both are dropped.
    fn leave_autonomy(&mut self) {
        self.follower.clear_trajectory();
        self.nav.following = None;
        self.nav.last_step = None;
        self.exploring.last_step = None;
    }

    /// Installs the clock that times planning (seconds, monotonic).
    pub fn set_stopwatch(&mut self, stopwatch: std::sync::Arc<dyn crate::clock::Clock>) {
        self.stopwatch = Some(stopwatch);
    }

    /// Commands the robot to stop and logs why; used on quit, signals and lost input.
    pub fn shutdown(&mut self, reason: &str) {
        self.teleop.clear();
        self.commanded = Twist::ZERO;
        self.link.stop();
        self.log(Level::Warn, format!("robot stopped: {reason}"));
    }

    // ----- read-only views for the renderer and the runners -----

    pub fn mode(&self) -> Mode {
        self.mode
    }
    pub fn now(&self) -> f64 {
        self.now
    }
    pub fn config(&self) -> &Config {
        &self.config
    }
    pub fn keymap(&self) -> &Keymap {
        &self.keymap
    }
    pub fn link(&self) -> &dyn RobotLink {
        self.link.as_ref()
    }
    pub fn link_status(&self) -> &LinkStatus {
        &self.link_status
    }
    pub fn log_book(&self) -> &LogBook {
        &self.log
    }
    pub fn view(&self) -> &ViewState {
        &self.view
    }
    pub fn teleop(&self) -> &Teleop {
        &self.teleop
    }
    pub fn estimated_pose(&self) -> Pose2 {
        self.ekf.pose()
    }
    pub fn odometry_distance(&self) -> f64 {
        self.odometry.distance()
    }
    pub fn true_pose(&self) -> Option<Pose2> {
        self.link.ground_truth().map(|t| t.pose())
    }
    pub fn commanded(&self) -> Twist {
        self.commanded
    }
    pub fn measured(&self) -> Twist {
        self.measured
    }
    pub fn gripper(&self) -> Option<GripperState> {
        self.gripper
    }
    pub fn estop(&self) -> bool {
        self.estop
    }
    pub fn should_quit(&self) -> bool {
        self.quit
    }
    /// IDs seen within the last `IN_VIEW_HOLD` seconds, sorted: steadier than one frame,
    /// whose set flickers with every missed detection.
    pub fn in_view(&self) -> Vec<u32> {
        let mut ids: Vec<u32> = self.in_view.iter().map(|(id, _)| *id).collect();
        ids.sort_unstable();
        ids
    }

    fn note_sightings(&mut self, t: f64, sightings: &[MarkerSighting]) {
        for s in sightings {
            match self.in_view.iter_mut().find(|(id, _)| *id == s.id) {
                Some(entry) => entry.1 = t,
                None => self.in_view.push((s.id, t)),
            }
        }
        self.in_view.retain(|(_, seen)| t - seen <= IN_VIEW_HOLD);
    }
    pub fn world_grid(&self) -> Option<&OccupancyGrid> {
        self.world_grid.as_ref()
    }
    pub fn loop_rate(&self) -> f64 {
        self.clock.rate()
    }
    pub fn screen(&self) -> (u16, u16) {
        self.screen
    }
    /// Drive keys currently held, for the status panel.
    pub fn held_keys(&self) -> Vec<Action> {
        self.teleop.clone().held_at(self.now, self.brake_margin())
    }

    /// Tells the console the terminal's size (the map scale depends on it).
    pub fn resize(&mut self, width: u16, height: u16) {
        self.screen = (width, height);
        self.refresh_revision();
    }

    /// Increases whenever something on screen changed: the TUI draws only then.
    pub fn revision(&self) -> u64 {
        self.revision
    }

    /// The world extent the map fits to: the twin's world, else 4 m x 4 m (seed 001's grid).
    pub fn world_extent(&self) -> (Point2, (f64, f64)) {
        match self.link.ground_truth() {
            Some(t) => (Point2::new(0.0, 0.0), (t.world().width, t.world().height)),
            None => (Point2::new(0.0, 0.0), (4.0, 4.0)),
        }
    }

    /// Metres per column that fits the world into the map area.
    pub fn fitted_scale(&self) -> f64 {
        let area = screen::map_area(self.screen);
        let (_, (w, h)) = self.world_extent();
        let cols = f64::from(area.2.max(1));
        // A terminal cell is about twice as tall as wide: rows cover twice a column's metres.
        let rows = f64::from(area.3.max(1));
        (w / cols).max(h / (2.0 * rows)) * 1.02
    }

    /// The map's centre point in the world.
    pub fn map_center(&self) -> Point2 {
        if let Some(c) = self.view.center {
            return c;
        }
        if self.view.zoom.is_none() {
            self.world_extent().0
        } else {
            self.estimated_pose().position()
        }
    }

    /// Visible span of the map in metres (width, height).
    pub fn map_span(&self) -> (f64, f64) {
        let area = screen::map_area(self.screen);
        let scale = self.view.scale(self.fitted_scale());
        (f64::from(area.2) * scale, f64::from(area.3) * 2.0 * scale)
    }
}

impl Drop for App {
    /// However the console ends, even by panic, the robot is told to stop.
    fn drop(&mut self) {
        self.link.stop();
    }
}
