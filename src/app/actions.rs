//! Where an action goes: its route in the action table (`keymap::action`) sends it to
//! the pilot or to one of the console's own handlers. Typed commands come through here too.

use super::command::{Intent, Typed};
use super::log::Level;
use super::{App, saving};
use crate::geometry::Point2;
use crate::keymap::action::{Handler, Route};
use crate::pilot::{self, mode::Mode, navigation::Target};

impl App {
    /// The one place the console's state changes: a key's action or a typed command.
    pub fn apply(&mut self, intent: impl Into<Intent>) {
        let action = match intent.into() {
            Intent::Action(action) => action,
            Intent::Typed(typed) => return self.apply_typed(typed),
        };
        let ask = match action.route() {
            Route::Drive(key) => pilot::Intent::KeyDown { key, repeat: false },
            Route::Speed(change) => pilot::Intent::Speed(change),
            Route::Pilot(ask) => ask,
            Route::Console(handler) => return self.apply_to_console(handler),
        };
        self.run_intent(ask);
    }

    /// The handlers that change the console (and, for a few, ask the pilot in its stead).
    fn apply_to_console(&mut self, handler: Handler) {
        let load = self.pilot().mode() == Mode::Load;
        let route = self.pilot().mode() == Mode::Route;
        match handler {
            Handler::Quit => {
                self.shutdown("quit by user");
                self.quit = true;
            }
            Handler::Help => self.view.help = !self.view.help,
            Handler::Zoom(inward) => {
                let fitted = self.fitted_scale();
                self.view.zoom_step(fitted, inward);
            }
            Handler::Pan(dx, dy) => {
                let from = self.map_center();
                let span = self.map_span();
                self.view.pan(from, span, dx, dy);
            }
            Handler::CenterView => {
                self.view.center = None;
                self.view.zoom = None;
            }
            Handler::ToggleBraille => self.view.braille = !self.view.braille,
            // Off, all landmarks, gates and blocks only, off.
            Handler::CycleLandmarks => {
                let table = &mut self.view.table;
                match (self.view.landmarks, table.targets_only) {
                    (false, _) => {
                        self.view.landmarks = true;
                        table.targets_only = false;
                    }
                    (true, false) => table.targets_only = true,
                    (true, true) => self.view.landmarks = false,
                }
                table.selected = 0;
            }
            Handler::CycleCamera => self.view.camera = self.view.camera.next(),
            Handler::ToggleScan => self.view.scan = !self.view.scan,
            Handler::ToggleTrail => self.view.trail = !self.view.trail,
            Handler::ToggleGraph => {
                if self.pilot().lidar_slam().is_some() {
                    self.view.graph = !self.view.graph;
                } else {
                    self.log(
                        Level::Warn,
                        "the pose graph exists only with lidar SLAM (--estimator slam)",
                    );
                }
            }
            Handler::LogOlder => {
                let shown = self.log.iter().filter(|e| self.view.log.shows(e)).count();
                let page = self.log_page();
                let back = self.view.log.back + page;
                self.view.log.back = back.min(shown.saturating_sub(page));
            }
            Handler::LogNewer => {
                self.view.log.back = self.view.log.back.saturating_sub(self.log_page());
            }
            Handler::LogFilter => self.view.log.next_level(),
            Handler::LogSource => self.view.log.next_source(),
            Handler::LogSearch => self.prompt.open("/"),
            Handler::ToggleTruth => {
                if self.link().ground_truth().is_some() {
                    self.view.show_truth = !self.view.show_truth;
                } else {
                    self.log(Level::Warn, "true pose exists only in the twin");
                }
            }
            // In load mode up and down pick a map instead.
            Handler::Cursor(_, dy) if load && dy != 0.0 => self.pick(if dy > 0.0 { -1 } else { 1 }),
            // In route mode they choose a task or a tag.
            Handler::Cursor(_, dy) if route && dy != 0.0 => {
                self.pick_route(if dy > 0.0 { -1 } else { 1 })
            }
            Handler::Cursor(dx, dy) => self.move_cursor(dx, dy),
            Handler::PlanToCursor if load => self.load_selected(),
            Handler::PlanToCursor if route => self.drive_picked_route(),
            Handler::PlanToCursor => {
                let goal = self
                    .cursor
                    .unwrap_or_else(|| self.pilot().estimated_pose().position());
                self.run_intent(pilot::Intent::Goto(Target::Point(goal)));
            }
            Handler::PoseEstimate => self.pose_estimate_key(),
            Handler::AddWaypoint => self.add_waypoint(None),
            Handler::ZoneCorner(speed) => self.zone_corner(speed),
            Handler::CommandLine => self.prompt.open(""),
            Handler::SaveMap => {
                self.save_map(saving::SAVE_KEY_NAME);
            }
            Handler::Fleet(ask) => self.ask_fleet(ask),
            Handler::Nothing => {}
        }
    }

    /// Acts on a typed command.
    fn apply_typed(&mut self, typed: Typed) {
        match typed {
            Typed::GotoPoint(p) => {
                self.cursor = self.cursor.map(|_| p);
                self.run_intent(pilot::Intent::Goto(Target::Point(p)));
            }
            Typed::GotoPose(pose) => {
                self.cursor = self.cursor.map(|_| pose.position());
                self.run_intent(pilot::Intent::Goto(Target::Pose(pose)));
            }
            Typed::GotoMarker(id) => self.run_intent(pilot::Intent::Goto(Target::Marker(id))),
            Typed::Controller(kind) => self.run_intent(pilot::Intent::Controller(kind)),
            Typed::RestartMission => self.run_intent(pilot::Intent::RestartMission),
            Typed::SetPose(pose) => self.run_intent(pilot::Intent::SetPose(pose)),
            Typed::Relocalize => self.run_intent(pilot::Intent::Relocalize),
            Typed::Localise => self.start_localising(),
            Typed::WhichController => {
                let now = self.pilot().follower().controller().label();
                self.log(
                    Level::Info,
                    format!("path controller: {now} (:controller pid|pure_pursuit|hybrid)"),
                );
            }
            Typed::Save(name) => {
                self.save_map(&name);
            }
            Typed::AddWaypoint(w) => self.add_waypoint(Some(w)),
            Typed::AddCursorWaypoint => self.add_waypoint(None),
            Typed::Route(ask) => self.run_intent(pilot::Intent::Route(ask)),
            Typed::SaveRoute(name) => self.save_route(&name),
            Typed::LoadRoute(name) => self.load_route(&name),
            Typed::ShowRoute => self.show_route(),
            Typed::TagRoute(goal) => self.run_intent(pilot::Intent::TagRoute(goal)),
            Typed::ShowBehaviours => self.show_behaviours(),
            Typed::SwitchBehaviour {
                behaviour,
                on,
                seconds,
            } => self.run_intent(pilot::Intent::Behaviour {
                behaviour,
                on,
                seconds,
            }),
            Typed::Fault(spec) => self.inject_fault(&spec),
            Typed::ClearFaults => self.clear_faults(),
            Typed::ShowFaults => self.show_faults(),
            Typed::Zone(z) => self.apply_zone(z),
            Typed::Robot(name) => self.ask_fleet(super::fleet_view::FleetAsk::Select(name)),
            Typed::AddRobot(ns) => self.ask_fleet(super::fleet_view::FleetAsk::Add(ns)),
        }
    }

    /// `:behaviours`: which behaviour drives, and the arbiter's transitions kept (the last
    /// 100, newest last), in the log.
    fn show_behaviours(&mut self) {
        let arbiter = self.pilot().arbiter();
        let now = match arbiter.winner() {
            Some((b, "")) => format!("behaviour now: {b}"),
            Some((b, why)) => format!("behaviour now: {b} ({why})"),
            None => "behaviour now: idle".to_string(),
        };
        let lines: Vec<String> = (arbiter.history())
            .map(|tr| format!("{:7.1} s {}", tr.t, tr.text()))
            .collect();
        self.log(
            Level::Info,
            format!("{now}; the last {} changes:", lines.len()),
        );
        for line in lines {
            self.log(Level::Info, line);
        }
    }

    /// Moves thinking mode's goal cursor by (dx, dy) screen cells; the map pans to keep
    /// it in view.
    fn move_cursor(&mut self, dx: f64, dy: f64) {
        let scale = self.view.scale(self.fitted_scale());
        let c = self
            .cursor
            .unwrap_or_else(|| self.pilot().estimated_pose().position());
        // One screen cell: a row is twice as tall as a column is wide.
        let moved = Point2::new(c.x + dx * scale, c.y + dy * 2.0 * scale);
        self.cursor = Some(moved);
        let (centre, (w, h)) = (self.map_center(), self.map_span());
        // Off the map: pan by whole cells so the cursor stays one cell inside the edge.
        let (half_w, half_h) = (w / 2.0 - scale, h / 2.0 - 2.0 * scale);
        let shift = |d: f64, half: f64| {
            if d > half {
                d - half
            } else if d < -half {
                d + half
            } else {
                0.0
            }
        };
        let (sx, sy) = (
            shift(moved.x - centre.x, half_w),
            shift(moved.y - centre.y, half_h),
        );
        if sx != 0.0 || sy != 0.0 {
            self.view.center = Some(Point2::new(centre.x + sx, centre.y + sy));
        }
    }
}
