//! Deciding when the screen needs drawing: a redraw is due only when a value shown on it
//! changes at the precision it is shown with.

use super::mode::Mode;
use super::view::ViewState;
use super::{App, LinkStatus};
use crate::control::config::ControllerKind;
use crate::data::GripperState;

/// The rounded values the screen shows; a change means a redraw is due.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Visible {
    mode: Mode,
    pose: (i64, i64, i64),
    truth: Option<(i64, i64, i64)>,
    commanded: (i64, i64),
    measured: (i64, i64),
    speeds: (i64, i64),
    second: i64,
    loop_rate: i64,
    log: u64,
    gripper: Option<GripperState>,
    estop: bool,
    held: usize,
    link: LinkStatus,
    view: ViewState,
    screen: (u16, u16),
    collisions: u32,
    sightings: Vec<u32>,
    blocks: Vec<(i64, i64)>,
    map: u64,
    cursor: Option<(i64, i64)>,
    prompt: Option<String>,
    following: Option<(i64, i64, i64)>,
    route: Option<(i64, String)>,
    controller: ControllerKind,
    arrived: bool,
    picked: usize,
    maps: usize,
    /// Camera frames, while the camera panel shows them.
    camera: Option<u64>,
}

fn centi(v: f64) -> i64 {
    (v * 100.0).round() as i64
}

impl App {
    /// The map revision the screen should show: the newest as of the current second. A scan
    /// changes a few cells at a time, mostly finer than a screen cell shows, so the map
    /// alone redraws only with the clock, once a second.
    fn shown_map_revision(&mut self) -> u64 {
        let second = self.now.floor();
        if second > self.map_shown.1 {
            self.map_shown = (self.belief.revision(), second);
        }
        self.map_shown.0
    }

    pub(super) fn refresh_revision(&mut self) {
        let map = self.shown_map_revision();
        let pose = self.estimated_pose();
        let deg = |t: f64| t.to_degrees().round() as i64;
        let twin = self.link.ground_truth();
        let visible = Visible {
            mode: self.mode,
            pose: (centi(pose.x), centi(pose.y), deg(pose.theta)),
            truth: twin.map(|t| {
                let p = t.pose();
                (centi(p.x), centi(p.y), deg(p.theta))
            }),
            commanded: (centi(self.commanded.linear), centi(self.commanded.angular)),
            measured: (centi(self.measured.linear), centi(self.measured.angular)),
            speeds: (
                centi(self.teleop.linear_speed),
                centi(self.teleop.angular_speed),
            ),
            second: self.now.floor() as i64,
            loop_rate: self.clock.rate().round() as i64,
            log: self.log.written(),
            gripper: self.gripper,
            estop: self.estop,
            held: self.held_keys().len(),
            link: self.link_status.clone(),
            map,
            cursor: self.nav.cursor.map(|c| (centi(c.x), centi(c.y))),
            prompt: self.nav.prompt.clone(),
            following: self.nav.following.map(|f| {
                (
                    centi(f.remaining),
                    (f.eta * 10.0).round() as i64,
                    (f.cross_track * 1000.0).round() as i64,
                )
            }),
            route: self
                .nav
                .route
                .as_ref()
                .map(|r| (centi(r.plan.length), r.label.clone())),
            controller: self.follower.controller(),
            arrived: self.nav.arrived,
            picked: self.picker.selected,
            maps: self.picker.entries.len(),
            view: self.view.clone(),
            screen: self.screen,
            collisions: twin.map_or(0, |t| t.collisions()),
            sightings: self.in_view(),
            blocks: twin.map_or(Vec::new(), |t| {
                t.blocks()
                    .iter()
                    .map(|b| (centi(b.pose.x), centi(b.pose.y)))
                    .collect()
            }),
            camera: (self.view.camera != super::view::CameraPanel::Off)
                .then_some(self.camera.frames),
        };
        if self.visible.as_ref() != Some(&visible) {
            self.visible = Some(visible);
            self.revision += 1;
        }
    }
}
