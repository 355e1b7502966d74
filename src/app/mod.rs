//! The console around the pilot: the link, the keymap, the view, the log, thinking
//! mode's cursor, the `:` prompt, the map picker and map files. Keys become actions;
//! what concerns the robot goes to the pilot as an intent, the rest changes the console.
//!
//! Free of terminal and clock: time is passed in as `now` (seconds on the session
//! clock). The TUI passes wall time, the headless runner and the tests simulated time.

mod actions;
mod camera_feed;
mod command;
mod control;
mod faults;
pub mod fleet_view;
pub mod loading;
mod localising;
pub mod log;
mod pose_estimate;
mod prompt;
mod recording;
mod revision;
mod route_file;
mod route_picker;
mod saving;
pub mod zones;
pub use saving::save_map_files;
pub mod screen;
mod table;
pub mod view;

use crate::config::Config;
use crate::data::MarkerSighting;
use crate::geometry::{Point2, Pose2};
use crate::keymap::Action;
use crate::keymap::{Key, Keymap};
use crate::link::RobotLink;
use crate::link::runtime::Runtime;
use crate::link::runtime::localising::LocalisingMove;
use crate::map::grid::OccupancyGrid;
use crate::pilot::{self, Pilot};
use log::{Level, LogBook};
use mode::Mode;
use view::ViewState;

pub use crate::pilot::LinkStatus;
pub use crate::pilot::mode;

/// What a key event was: terminals without the kitty protocol only ever report `Press`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum KeyKind {
    Press,
    Repeat,
    Release,
}

/// How long a marker stays marked "in view" after its last sighting, seconds.
pub const IN_VIEW_HOLD: f64 = 0.5;

/// Resolution of the world raster drawn on the map, metres.
pub const WORLD_RASTER: f64 = 0.02;

/// The console around the pilot: the link, the keys, the screen and the log.
pub struct App {
    config: Config,
    keymap: Keymap,
    /// The robot: its link, its pilot (everything that decides how it moves), the control
    /// schedule and the recording.
    runtime: Runtime,
    log: LogBook,
    view: ViewState,
    /// Terminal size in cells, as last reported.
    screen: (u16, u16),
    quit: bool,
    /// Marker IDs and when each was last seen: the map marks them "in view" for a while.
    in_view: Vec<(u32, f64)>,
    world_grid: Option<OccupancyGrid>,
    /// Thinking mode's goal cursor, and the command being typed after `:`.
    cursor: Option<Point2>,
    /// A pose estimate's position, placed and waiting for its heading.
    pose_anchor: Option<Point2>,
    prompt: prompt::Prompt,
    files: saving::Files,
    picker: loading::Picker,
    redraw: revision::Redraw,
    camera: camera_feed::CameraFeed,
    /// `:localise`: the move that tells MCL's hypotheses apart, while it drives.
    localising: Option<LocalisingMove>,
    /// A keepout or speed zone being drawn with the cursor.
    zone_drawing: zones::Drawing,
    /// Route mode's chosen row: a task or a tag (`route_picker.rs`).
    route_pick: usize,
    /// What this console asks of its fleet, and the other robots on its map.
    fleet: fleet_view::FleetView,
}

impl App {
    /// A console on `link`, starting at session time `now`.
    pub fn new(config: Config, keymap: Keymap, link: Box<dyn RobotLink>, now: f64) -> Self {
        let truth = link.ground_truth();
        let world_grid = truth.map(|t| t.world().rasterize(WORLD_RASTER));
        let runtime = Runtime::new(link, config.pilot_settings(), now);
        let mut app = Self {
            runtime,
            keymap,
            log: LogBook::new(500),
            view: ViewState::default(),
            screen: (80, 24),
            quit: false,
            in_view: Vec::new(),
            world_grid,
            cursor: None,
            pose_anchor: None,
            zone_drawing: zones::Drawing::default(),
            prompt: prompt::Prompt::default(),
            files: saving::Files::new(now),
            picker: loading::Picker::default(),
            redraw: revision::Redraw::default(),
            camera: camera_feed::CameraFeed::default(),
            localising: None,
            route_pick: 0,
            fleet: fleet_view::FleetView::default(),
            config,
        };
        if app.link().takes_log() {
            app.log.keep_fresh();
        }
        let label = app.link().label();
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
        self.log.push(self.now(), level, text);
    }

    /// Localises with MCL, or continues a saved map with lidar SLAM, as the session
    /// chose (`--estimator mcl`, `--estimator slam --map`).
    pub fn localize(&mut self, localizer: &crate::pilot::localize::Localizer) {
        if let Err(why) = localizer.apply(self.runtime.pilot_mut()) {
            let what = localizer.label();
            self.log(Level::Error, format!("{what} not started: {why}"));
        }
        self.refresh_revision();
    }

    /// Why lane mode cannot run on this robot (no lane camera), or None when it can.
    pub fn set_lane_unavailable(&mut self, why: Option<String>) {
        self.runtime.pilot_mut().set_lane_unavailable(why);
    }

    /// A warning from outside the core (the console's own set-up) into the log.
    pub fn warn(&mut self, text: impl Into<String>) {
        self.log(Level::Warn, text);
        self.refresh_revision();
    }

    /// Every log line, those so far first, also goes to `sink` (the session's log file).
    pub fn log_to(&mut self, sink: log::Sink) -> std::io::Result<()> {
        self.log.set_sink(sink)
    }

    /// Resolves a key through the active mode's keymap and acts on it.
    pub fn handle_key(&mut self, key: Key, kind: KeyKind, now: f64) {
        let event = crate::msgs::record::InputMsg::key(now, key.to_string(), kind as u8);
        self.record_input(event);
        self.handle_key_inner(key, kind, now);
        self.pass_log();
    }

    fn handle_key_inner(&mut self, key: Key, kind: KeyKind, now: f64) {
        self.advance_to(now);
        if kind == KeyKind::Press && self.pilot().link_status() == &LinkStatus::Back {
            // Control resumes only on the user's word after a loss (the key is not acted on).
            self.run_intent(pilot::Intent::Resume);
            self.refresh_revision();
            return;
        }
        let mode = self.pilot().mode();
        let action = self.keymap.lookup(mode, key).or_else(|| {
            // In the autonomous modes the manual drive keys take control back.
            self.keymap
                .lookup(Mode::Manual, key)
                .filter(|a| a.motion().is_some() && !mode.drives_by_keys())
        });
        let drive = action.and_then(Action::motion);
        if kind == KeyKind::Release {
            // Only terminals speaking the kitty protocol send releases.
            match drive.filter(|_| self.prompt.line.is_none()) {
                Some(key) => self.run_intent(pilot::Intent::KeyUp(key)),
                None => self.run_intent(pilot::Intent::ReleasesReported),
            }
            return;
        }
        if self.prompt.line.is_some() {
            self.edit_prompt(key);
            return;
        }
        if self.view.help {
            // Any key closes the help overlay and does nothing else.
            self.view.help = false;
            return;
        }
        if self.view.landmarks && self.table_key(key) {
            self.refresh_revision();
            return;
        }
        let Some(action) = action else {
            return;
        };
        match drive {
            Some(key) => self.run_intent(pilot::Intent::KeyDown {
                key,
                repeat: kind == KeyKind::Repeat,
            }),
            None if kind == KeyKind::Press => self.apply(action),
            None => {}
        }
    }

    /// Runs a command typed after `:` through the same door as keys.
    fn run_command(&mut self, line: &str) {
        match command::parse(line) {
            Ok(intent) => self.apply(intent),
            Err(e) => self.log(Level::Error, format!(":{line}: {e}")),
        }
    }

    /// Installs the clock that times planning (seconds, monotonic).
    pub fn set_stopwatch(&mut self, stopwatch: std::sync::Arc<dyn crate::clock::Clock>) {
        self.runtime.pilot_mut().set_stopwatch(stopwatch);
    }

    /// Commands the robot to stop and logs why; used on quit, signals and lost input.
    pub fn shutdown(&mut self, reason: &str) {
        self.run_intent(pilot::Intent::Halt);
        self.runtime.stop();
        self.log(Level::Warn, format!("robot stopped: {reason}"));
    }

    // ----- read-only views for the renderer and the runners -----

    /// Everything that decides how the robot moves: mode, estimate, map, route, mission.
    pub fn pilot(&self) -> &Pilot {
        self.runtime.pilot()
    }
    pub fn now(&self) -> f64 {
        self.runtime.now()
    }
    pub fn config(&self) -> &Config {
        &self.config
    }
    pub fn keymap(&self) -> &Keymap {
        &self.keymap
    }
    pub fn link(&self) -> &dyn RobotLink {
        self.runtime.link()
    }
    pub fn log_book(&self) -> &LogBook {
        &self.log
    }
    pub fn view(&self) -> &ViewState {
        &self.view
    }
    /// The twin's true pose, when the link has a simulator behind it.
    pub fn true_pose(&self) -> Option<Pose2> {
        self.link().ground_truth().map(|t| t.pose())
    }
    pub fn should_quit(&self) -> bool {
        self.quit
    }
    /// Thinking mode's goal cursor.
    pub fn goal_cursor(&self) -> Option<Point2> {
        self.cursor
    }
    /// The command being typed after `:`.
    pub fn prompt(&self) -> Option<&str> {
        self.prompt.line.as_deref()
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
        self.runtime.loop_rate()
    }
    pub fn screen(&self) -> (u16, u16) {
        self.screen
    }
    /// Drive keys currently held, for the status panel.
    pub fn held_keys(&self) -> Vec<Action> {
        let keys = self.pilot().held_keys(self.now());
        keys.into_iter().filter_map(Action::driving).collect()
    }

    /// Log lines a page-back key moves: the pane's rows (its height less the two border
    /// rows) less one kept for context.
    fn log_page(&self) -> usize {
        let (_, _, _, h) = screen::layout(self.screen).log;
        usize::from(h.saturating_sub(3)).max(1)
    }

    /// Tells the console the terminal's size (the map scale depends on it).
    pub fn resize(&mut self, width: u16, height: u16) {
        self.record_input(crate::msgs::record::InputMsg::resize(
            self.now(),
            width,
            height,
        ));
        self.screen = (width, height);
        self.refresh_revision();
    }

    /// The world extent the map fits to: the twin's world, else 4 m x 4 m (seed 001's grid).
    pub fn world_extent(&self) -> (Point2, (f64, f64)) {
        // On a known map, the place it maps: its walls' box, not the whole image.
        if let Some(mcl) = self.pilot().mcl() {
            let (lo, hi) = mcl.map().occupied_bounds();
            let centre = Point2::new((lo.x + hi.x) / 2.0, (lo.y + hi.y) / 2.0);
            return (centre, (hi.x - lo.x, hi.y - lo.y));
        }
        match self.link().ground_truth() {
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
            self.pilot().estimated_pose().position()
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
        self.runtime.link_mut().stop();
    }
}
