//! What navdeck believes, handed to links that show it elsewhere (RViz over ROS 2).

use super::App;
use crate::link::Picture;

impl App {
    /// The pose every control step; the map, landmarks and plan at the link's period.
    pub(super) fn show_picture(&mut self, t: f64) {
        let Some(period) = self.link.picture_period() else {
            return;
        };
        let full = t - self.picture_at >= period - 1e-9;
        if full {
            self.picture_at = t;
        }
        let picture = Picture {
            stamp: t,
            pose: self.ekf.pose(),
            pose_covariance: self.ekf.pose_covariance(),
            landmarks: full.then(|| self.ekf.landmarks().collect()),
            // An empty path clears the last one from the display.
            path: full.then(|| {
                self.route()
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
            // display that joins later still gets the last one.
            map: (full && self.picture_map != Some(self.belief.revision()))
                .then(|| self.belief.occupancy_grid()),
        };
        if picture.map.is_some() {
            self.picture_map = Some(self.belief.revision());
        }
        self.link.show(&picture);
    }
}
