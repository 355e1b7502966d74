//! Route mode's list (seed 003 §2.2): the tag map's tasks, then its tags, one chosen with
//! the arrows and driven with enter, as the landmark table and the map picker choose.

use super::App;
use super::log::Level;
use crate::pilot;
use crate::pilot::tag_route::TagGoal;
use crate::sim::tag_camera::TagCamera;
use crate::tags::TagMap;
use crate::tags::drive::{DriveGains, DriveSetup};
use std::sync::Arc;

impl App {
    /// Lays the tag map route mode drives on (`--tags`), seen by the twin's tag camera's
    /// mount; None leaves route mode saying what to pass.
    pub fn set_tag_map(&mut self, map: Option<(Arc<TagMap>, f64)>) {
        let (map, look) = match map {
            Some((map, look)) => (Some(map), look),
            None => (None, TagCamera::default().look),
        };
        let setup = match &map {
            Some(map) => DriveSetup {
                gains: DriveGains::from_map(map),
                look,
                ..DriveSetup::default()
            },
            None => DriveSetup::default(),
        };
        if let Some(map) = &map {
            let text = format!(
                "tag map: {} tags, {} tasks; i for route mode",
                map.tags.len(),
                map.tasks.len()
            );
            self.log(Level::Info, text);
        }
        self.runtime.pilot_mut().set_tag_map(map, setup);
        self.route_pick = 0;
        self.refresh_revision();
    }

    /// What route mode's list offers: every task by name, then every tag by id.
    pub fn route_choices(&self) -> Vec<TagGoal> {
        let Some(map) = self.pilot().tag_route().map() else {
            return Vec::new();
        };
        let tasks = map.tasks.keys().map(|name| TagGoal::Task(name.clone()));
        tasks
            .chain(map.tags.keys().map(|&id| TagGoal::Tag(id)))
            .collect()
    }

    /// The chosen row of route mode's list.
    pub fn route_pick(&self) -> usize {
        self.route_pick
    }

    /// Moves the choice `delta` rows, within the list.
    pub(super) fn pick_route(&mut self, delta: i64) {
        let last = self.route_choices().len().saturating_sub(1) as i64;
        self.route_pick = (self.route_pick as i64 + delta).clamp(0, last.max(0)) as usize;
    }

    /// Drives the chosen task, or to the chosen tag.
    pub(super) fn drive_picked_route(&mut self) {
        match self.route_choices().get(self.route_pick).cloned() {
            Some(goal) => self.run_intent(pilot::Intent::TagRoute(goal)),
            None => {
                // The pilot says what to pass for a map.
                self.run_intent(pilot::Intent::Mode(pilot::mode::Mode::Route));
            }
        }
    }
}
