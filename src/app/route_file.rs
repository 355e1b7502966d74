//! The waypoint route on disk and in the log: `:route save`, `:route load`, `:route show`,
//! and queueing the goal cursor as a waypoint.

use super::App;
use super::log::Level;
use crate::pilot;
use crate::pilot::waypoints::file::{self, RouteFile};
use crate::pilot::waypoints::{RouteAsk, Waypoint};
use std::path::PathBuf;

impl App {
    /// Where a route named `name` lives: NAME.route.yaml in the maps folder, or the path
    /// as typed when it has a `/` or ends in `.yaml`.
    fn route_path(&self, name: &str) -> Option<PathBuf> {
        if name.contains('/') || name.ends_with(".yaml") {
            return Some(PathBuf::from(name));
        }
        let dir = self.files.maps_dir.as_ref()?;
        Some(dir.join(format!("{name}.route.yaml")))
    }

    pub(super) fn save_route(&mut self, name: &str) {
        let Some(path) = self.route_path(name) else {
            return self.log(Level::Error, format!("route {name} not saved: this session has no maps folder (give a path: :route save dir/{name}.yaml)"));
        };
        let w = self.pilot().waypoints();
        if w.goals().is_empty() {
            return self.log(Level::Warn, "route not saved: no waypoints (:waypoint add)");
        }
        let route = RouteFile {
            waypoints: w.goals().to_vec(),
            loops: w.loops(),
        };
        let n = route.waypoints.len();
        // As a map save: a name with control characters refused, never through a link,
        // the route it replaces kept as .bak.
        let written = crate::data::replace::replace_file(&path, file::to_yaml(&route).into_bytes());
        match written.map_err(|(_, e)| crate::map::io::io_reason(&e)) {
            Ok(()) => self.log(
                Level::Success,
                format!("route saved: {} ({n} waypoints)", path.display()),
            ),
            Err(e) => self.log(
                Level::Error,
                format!("route not saved: cannot write {}: {e}", path.display()),
            ),
        }
    }

    pub(super) fn load_route(&mut self, name: &str) {
        let Some(path) = self.route_path(name) else {
            return self.log(
                Level::Error,
                format!("route {name} not loaded: this session has no maps folder (give a path)"),
            );
        };
        let shown = path.display().to_string();
        let route = crate::data::files::read_text_limited(&path, crate::data::files::TEXT_LIMIT)
            .map_err(|e| format!("cannot read {shown}: {}", crate::map::io::io_reason(&e)))
            .and_then(|text| file::parse(&text, &shown).map_err(|e| e.to_string()));
        match route {
            Ok(route) => {
                self.log(Level::Info, format!("route loaded: {shown}"));
                self.run_intent(pilot::Intent::Route(RouteAsk::Load {
                    waypoints: route.waypoints,
                    loops: route.loops,
                }));
            }
            Err(why) => self.log(Level::Error, format!("route not loaded: {why}")),
        }
    }

    /// `:route show`: every waypoint, numbered as on the map, and the progress.
    pub(super) fn show_route(&mut self) {
        let w = self.pilot().waypoints();
        let Some(progress) = w.progress() else {
            return self.log(
                Level::Info,
                "no waypoints: :waypoint add, :goto+ X Y or W in thinking mode",
            );
        };
        let list: Vec<String> = w
            .goals()
            .iter()
            .enumerate()
            .map(|(i, g)| format!("{} {}", i + 1, g.target().label()))
            .collect();
        self.log(
            Level::Info,
            format!("route: {progress}: {}", list.join(", ")),
        );
    }

    /// Queues thinking mode's goal cursor (or a given waypoint) at the route's end.
    pub(super) fn add_waypoint(&mut self, waypoint: Option<Waypoint>) {
        let waypoint = match (waypoint, self.cursor) {
            (Some(w), _) => w,
            (None, Some(position)) => Waypoint {
                position,
                yaw: None,
            },
            (None, None) => {
                return self.log(
                    Level::Warn,
                    "no goal cursor: t for thinking mode, or :waypoint add X Y [THETA_DEG]",
                );
            }
        };
        self.run_intent(pilot::Intent::Route(RouteAsk::Add(waypoint)));
    }
}
