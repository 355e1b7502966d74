//! What navdeck believes, handed to links that show it elsewhere (RViz over ROS 2).

use super::Runtime;
use super::state::MissionState;
use super::tag_graph;
use crate::Picture;

/// When the full picture last went to the link, and the map revision it carried.
#[derive(Clone, Debug)]
pub(super) struct Shown {
    at: f64,
    map: Option<u64>,
    /// The console's state as last shown.
    state: Option<MissionState>,
}

impl Default for Shown {
    fn default() -> Self {
        Self {
            at: f64::NEG_INFINITY,
            map: None,
            state: None,
        }
    }
}

impl Runtime {
    /// The pose every control step; the map, landmarks, plan and tag graph at the link's
    /// period.
    pub(super) fn show_picture(&mut self, t: f64) {
        let Some(period) = self.link.picture_period() else {
            return;
        };
        let full = t - self.shown.at >= period - 1e-9;
        if full {
            self.shown.at = t;
        }
        // The state goes out when it changed (its topic is latched for late joiners).
        let state = MissionState::of(&self.pilot);
        let state_changed = self.shown.state.as_ref() != Some(&state);
        let (slam, belief) = (self.pilot.slam(), self.pilot.belief());
        let picture = Picture {
            stamp: t,
            // The pose the robot decides with: MCL's when it runs.
            pose: self.pilot.estimated_pose(),
            pose_covariance: self.pilot.pose_covariance(),
            particles: (self.pilot.mcl())
                .filter(|_| full)
                .map(|m| m.particles().iter().map(|p| p.pose).collect()),
            landmarks: full.then(|| slam.landmarks().collect()),
            // An empty path clears the last one from the display.
            path: full.then(|| {
                self.pilot
                    .route()
                    .map(|r| {
                        r.plan
                            .trajectory
                            .points
                            .iter()
                            .map(|p| p.position)
                            .collect()
                    })
                    .unwrap_or_default()
            }),
            // The map goes out only when it changed: its topic is transient local, so a
            // display that joins later still gets the last one. With lidar SLAM it is the
            // lidar's map, as slam_toolbox publishes.
            map: (full && self.shown.map != Some(belief.revision()))
                .then(|| self.pilot.map_to_save()),
            state: state_changed.then(|| state.to_json()),
            tag_graph: full
                .then(|| tag_graph::picture(self.pilot.tag_route()))
                .flatten(),
        };
        if state_changed {
            self.shown.state = Some(state);
        }
        if picture.map.is_some() {
            self.shown.map = Some(belief.revision());
        }
        self.link.show(&picture);
    }
}
