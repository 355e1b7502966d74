//! Deciding when the screen needs drawing: a redraw is due only when a value shown on it
//! changes at the precision it is shown with.

use super::mode::Mode;
use super::view::ViewState;
use super::{App, LinkStatus};
use crate::control::config::ControllerKind;
use crate::data::GripperState;
use crate::pilot::Pilot;

/// Whether the screen needs drawing: the values last drawn and a counter of changes.
#[derive(Clone, Debug)]
pub(super) struct Redraw {
    revision: u64,
    visible: Option<Visible>,
    /// The map revision on screen and the session second it was taken in.
    map_shown: (u64, f64),
}

impl Default for Redraw {
    fn default() -> Self {
        Self {
            revision: 0,
            visible: None,
            map_shown: (0, f64::NEG_INFINITY),
        }
    }
}

/// The rounded values the screen shows; a change means a redraw is due.
#[derive(Clone, Debug, PartialEq)]
struct Visible {
    robot: RobotShown,
    route: RouteShown,
    console: ConsoleShown,
}

/// The robot's rows: mode, pose, speeds, gripper, link, contacts.
#[derive(Clone, Debug, PartialEq)]
struct RobotShown {
    mode: Mode,
    pose: (i64, i64, i64),
    truth: Option<(i64, i64, i64)>,
    commanded: (i64, i64),
    measured: (i64, i64),
    speeds: (i64, i64),
    loop_rate: i64,
    gripper: Option<GripperState>,
    estop: bool,
    held: usize,
    link: LinkStatus,
    collisions: u32,
}

/// The map's contents and the route on it.
#[derive(Clone, Debug, PartialEq)]
struct RouteShown {
    sightings: Vec<u32>,
    blocks: Vec<(i64, i64)>,
    map: u64,
    following: Option<(i64, i64, i64)>,
    route: Option<(i64, String)>,
    controller: ControllerKind,
    arrived: bool,
}

/// The console's own state: clock, log, view, cursor, prompt, map picker, camera panel.
#[derive(Clone, Debug, PartialEq)]
struct ConsoleShown {
    second: i64,
    log: u64,
    /// Whether a flashed log line shows.
    flash: bool,
    view: ViewState,
    screen: (u16, u16),
    cursor: Option<(i64, i64)>,
    prompt: Option<String>,
    picked: usize,
    maps: usize,
    /// Camera frames, while the camera panel shows them.
    camera: Option<u64>,
}

fn centi(v: f64) -> i64 {
    (v * 100.0).round() as i64
}

impl App {
    /// Increases whenever something on screen changed: the TUI draws only then.
    pub fn revision(&self) -> u64 {
        self.redraw.revision
    }

    /// The map revision the screen should show: the newest as of the current second. A scan
    /// changes a few cells at a time, mostly finer than a screen cell shows, so the map
    /// alone redraws only with the clock, once a second.
    fn shown_map_revision(&mut self) -> u64 {
        let second = self.now().floor();
        let shown = &mut self.redraw.map_shown;
        if second > shown.1 {
            *shown = (self.runtime.pilot().belief().revision(), second);
        }
        shown.0
    }

    pub(super) fn refresh_revision(&mut self) {
        let map = self.shown_map_revision();
        let p: &Pilot = self.pilot();
        let pose = p.estimated_pose();
        let deg = |t: f64| t.to_degrees().round() as i64;
        let twin = self.link().ground_truth();
        let (commanded, measured, teleop) = (p.commanded(), p.measured(), p.teleop());
        let robot = RobotShown {
            mode: p.mode(),
            pose: (centi(pose.x), centi(pose.y), deg(pose.theta)),
            truth: twin.map(|t| {
                let p = t.pose();
                (centi(p.x), centi(p.y), deg(p.theta))
            }),
            commanded: (centi(commanded.linear), centi(commanded.angular)),
            measured: (centi(measured.linear), centi(measured.angular)),
            speeds: (centi(teleop.linear_speed), centi(teleop.angular_speed)),
            loop_rate: self.runtime.loop_rate().round() as i64,
            gripper: p.gripper(),
            estop: p.estop(),
            held: self.held_keys().len(),
            link: p.link_status().clone(),
            collisions: twin.map_or(0, |t| t.collisions()),
        };
        let route = RouteShown {
            sightings: self.in_view(),
            blocks: twin.map_or(Vec::new(), |t| {
                t.blocks()
                    .iter()
                    .map(|b| (centi(b.pose.x), centi(b.pose.y)))
                    .collect()
            }),
            map,
            following: p.following().map(|f| {
                (
                    centi(f.remaining),
                    (f.eta * 10.0).round() as i64,
                    (f.cross_track * 1000.0).round() as i64,
                )
            }),
            route: p.route().map(|r| (centi(r.plan.length), r.label.clone())),
            controller: p.follower().controller(),
            arrived: p.arrived(),
        };
        let console = ConsoleShown {
            second: self.now().floor() as i64,
            log: self.log.written(),
            flash: self.log.flashing(self.now()).is_some(),
            view: self.view.clone(),
            screen: self.screen,
            cursor: self.cursor.map(|c| (centi(c.x), centi(c.y))),
            prompt: self.prompt.line.clone(),
            picked: self.picker.selected,
            maps: self.picker.entries.len(),
            camera: (self.view.camera != super::view::CameraPanel::Off)
                .then_some(self.camera.frames),
        };
        let visible = Visible {
            robot,
            route,
            console,
        };
        if self.redraw.visible.as_ref() != Some(&visible) {
            self.redraw.visible = Some(visible);
            self.redraw.revision += 1;
        }
    }
}
