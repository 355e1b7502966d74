//! Feeding the planning map: landmarks from the filter, camera sight lines, lidar scans
//! and the robot's own footprint, all placed with the filter's pose.

use super::Pilot;
use navdeck_core::data::{GripperState, LaserScan, MarkerSighting};
use navdeck_core::geometry::{Point2, Pose2};
use navdeck_core::map::contact::JAWS;

/// The footprint is marked free again after the robot moved this far, metres.
const FOOTPRINT_STEP: f64 = 0.02;
/// A scan is folded into the map after the robot moved this far (m), turned this much (rad)
/// or this long (s) passed since the last one.
const SCAN_MOVE: f64 = 0.05;
const SCAN_TURN: f64 = 0.1;
const SCAN_EVERY: f64 = 2.0;
/// Sight lines stop this short of the marker: the marker's own surface is not free.
const SIGHT_LINE_MARGIN: f64 = 0.1;

/// Where the map was last updated from, so that the same view is not folded in again.
#[derive(Clone, Debug, Default)]
pub(super) struct Upkeep {
    last_footprint: Option<Point2>,
    /// Where and when the last scan was folded into the map.
    pub last_scan_pose: Option<(Pose2, f64)>,
    /// The newest scan and the estimated pose it was taken from, for the map view.
    pub newest_scan: Option<(Pose2, LaserScan)>,
    /// Where the robot has driven.
    pub trail: super::trail::Trail,
    /// What the last map load changed, for undoing it.
    pub before_load: Option<Box<super::map_load::BeforeLoad>>,
}

impl Pilot {
    pub(super) fn map_sightings(&mut self, sightings: &[MarkerSighting]) {
        let estimates: Vec<_> = self.ekf.landmarks().map(|l| (l.id, l.mean)).collect();
        self.belief.update_landmarks(estimates.iter().copied());
        let from = self.pose().position();
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
        let pose = self.pose();
        self.upkeep.newest_scan = Some((pose, scan.clone()));
        if !self.localized() {
            // A scan placed at a pose MCL has not settled on would draw walls where
            // there are none.
            return;
        }
        if let Some((last, at)) = self.upkeep.last_scan_pose {
            let moved = last.position().distance(pose.position());
            let turned = navdeck_core::geometry::wrap_angle(pose.theta - last.theta).abs();
            // Lidar SLAM keeps its own keyframes for the map: the planning map takes those
            // (slam_toolbox's minimum travel), and still a view every while.
            let (step, turn) = match self.lidar_slam() {
                Some(sp) if !sp.keyframed => (f64::INFINITY, f64::INFINITY),
                _ => (SCAN_MOVE, SCAN_TURN),
            };
            if moved < step && turned < turn && t - at < SCAN_EVERY {
                return;
            }
        }
        self.upkeep.last_scan_pose = Some((pose, t));
        let held = (self.hand.state == Some(GripperState::Holding)).then_some(JAWS);
        match self.mcl().map(|m| m.map().clone()) {
            // On a known map, scans fill in what it knows, never the unknown beyond its
            // walls (a beam out through a gap would paint free space there).
            Some(known) => {
                let step = known.resolution / 2.0;
                let mappable = move |p| known.is_known(p);
                self.belief
                    .observe_scan_within(pose, scan, held, (mappable, step));
            }
            None => self.belief.observe_scan_holding(pose, scan, held),
        }
    }

    pub(super) fn map_footprint(&mut self) {
        if !self.localized() {
            return;
        }
        let here = self.pose().position();
        self.upkeep.trail.note(here);
        if self
            .upkeep
            .last_footprint
            .is_some_and(|p| p.distance(here) < FOOTPRINT_STEP)
        {
            return;
        }
        self.upkeep.last_footprint = Some(here);
        self.belief
            .observe_footprint(here, self.settings.robot.footprint_radius);
    }
}
