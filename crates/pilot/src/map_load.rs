//! Taking a saved map (load mode, seed 001) and putting it back: the planning map and
//! the filter's landmarks as they were before, for a map loaded by mistake.

use super::Pilot;
use nalgebra::Matrix2;
use navdeck_core::data::Level;
use navdeck_core::geometry::Point2;
use navdeck_core::map::belief::BeliefMap;
use navdeck_core::map::io::MapFile;

/// What a map load changed, kept until the next load so that it can be undone.
#[derive(Clone, Debug)]
pub(super) struct BeforeLoad {
    source: String,
    belief: BeliefMap,
    /// The priors the load added, with the sightings each came with: one seen since is
    /// the robot's own and stays.
    added: Vec<(u32, u32)>,
}

impl Pilot {
    /// Takes a saved map's occupancy and landmarks (as priors the filter may refine).
    pub(super) fn adopt_map(&mut self, map: &MapFile, source: &str) {
        let belief = self.belief.clone();
        self.belief.absorb_grid(&map.grid);
        let mut added = Vec::new();
        let landmarks = map
            .extras
            .as_ref()
            .map(|e| e.landmarks.as_slice())
            .unwrap_or_default();
        for l in landmarks {
            let c = &l.covariance;
            let cov = Matrix2::new(c[0][0], c[0][1], c[1][0], c[1][1]);
            let mean = Point2::new(l.mean[0], l.mean[1]);
            if self.ekf.add_prior(l.id, mean, cov, l.sightings) {
                added.push((l.id, l.sightings));
            }
        }
        let estimates: Vec<_> = self.ekf.landmarks().map(|l| (l.id, l.mean)).collect();
        self.belief.update_landmarks(estimates);
        self.log(
            Level::Success,
            format!(
                "loaded {source}: {} x {} cells at {} m, {} landmarks ({} new to the filter)",
                map.grid.width,
                map.grid.height,
                map.grid.resolution,
                landmarks.len(),
                added.len()
            ),
        );
        self.upkeep.before_load = Some(Box::new(BeforeLoad {
            source: source.to_string(),
            belief,
            added,
        }));
    }

    /// Puts the planning map back as it was before the last load, and takes out the
    /// landmarks that load added and the robot has not seen since.
    pub(super) fn undo_map_load(&mut self) {
        let Some(before) = self.upkeep.before_load.take() else {
            self.log(Level::Warn, "no map load to undo");
            return;
        };
        let mut dropped = Vec::new();
        for (id, sightings) in before.added {
            let unseen = self
                .ekf
                .landmark(id)
                .is_some_and(|l| l.sightings <= sightings);
            if unseen && self.ekf.forget(id) {
                dropped.push(id);
            }
        }
        self.belief = before.belief;
        self.belief.drop_landmarks(&dropped);
        let estimates: Vec<_> = self.ekf.landmarks().map(|l| (l.id, l.mean)).collect();
        self.belief.update_landmarks(estimates);
        self.upkeep.last_scan_pose = None;
        self.log(
            Level::Success,
            format!(
                "load of {} undone: the planning map is as before it, {} of its landmarks taken out",
                before.source,
                dropped.len()
            ),
        );
    }

    /// Whether a map load can be undone.
    pub fn can_undo_map_load(&self) -> bool {
        self.upkeep.before_load.is_some()
    }
}
