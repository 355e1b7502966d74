//! Feeding the planning map: landmarks from the filter, camera sight lines, lidar scans
//! and the robot's own footprint, all placed with the filter's pose.

use super::App;
use crate::config::Config;
use crate::data::{LaserScan, MarkerSighting};
use crate::link::RobotLink;
use crate::map::belief::BeliefMap;

/// The footprint is marked free again after the robot moved this far, metres.
const FOOTPRINT_STEP: f64 = 0.02;
/// A scan is folded into the map after the robot moved this far (m), turned this much (rad)
/// or this long (s) passed since the last one.
const SCAN_MOVE: f64 = 0.05;
const SCAN_TURN: f64 = 0.1;
const SCAN_EVERY: f64 = 2.0;
/// Sight lines stop this short of the marker: the marker's own surface is not free.
const SIGHT_LINE_MARGIN: f64 = 0.1;

/// A map covering the config's extent, or the twin's world if that is larger.
pub(super) fn belief_map_for(config: &Config, link: &dyn RobotLink) -> BeliefMap {
    let m = &config.map;
    let (w, h) = link
        .ground_truth()
        .map_or((m.width, m.height), |t| (t.world().width, t.world().height));
    BeliefMap::new(m, (m.width.max(w), m.height.max(h)))
}

impl App {
    pub(super) fn map_sightings(&mut self, sightings: &[MarkerSighting]) {
        let estimates: Vec<_> = self.ekf.landmarks().map(|l| (l.id, l.mean)).collect();
        self.belief.update_landmarks(estimates.iter().copied());
        let from = self.ekf.pose().position();
        for s in sightings {
            if let Some(&(_, at)) = estimates.iter().find(|(id, _)| *id == s.id) {
                self.belief.observe_sight_line(from, at, SIGHT_LINE_MARGIN);
            }
        }
    }

    /// Folds in a scan when the robot has moved or turned enough since the last one, or a
    /// while has passed: the same view again and again adds no information, only
    /// overconfidence (gmapping's linearUpdate / angularUpdate / temporalUpdate).
    pub(super) fn map_scan(&mut self, t: f64, scan: &LaserScan) {
        let pose = self.ekf.pose();
        if let Some((last, at)) = self.last_scan_pose {
            let moved = last.position().distance(pose.position());
            let turned = crate::geometry::wrap_angle(pose.theta - last.theta).abs();
            if moved < SCAN_MOVE && turned < SCAN_TURN && t - at < SCAN_EVERY {
                return;
            }
        }
        self.last_scan_pose = Some((pose, t));
        self.belief.observe_scan(pose, scan);
    }

    pub(super) fn map_footprint(&mut self) {
        let here = self.ekf.pose().position();
        if self
            .last_footprint
            .is_some_and(|p| p.distance(here) < FOOTPRINT_STEP)
        {
            return;
        }
        self.last_footprint = Some(here);
        self.belief
            .observe_footprint(here, self.config.robot.footprint_radius);
    }

    /// The robot's planning map.
    pub fn belief(&self) -> &BeliefMap {
        &self.belief
    }
}
