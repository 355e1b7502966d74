//! The landmark layer: the costs seed 001 section 4 stamps around every landmark, kept
//! up to date by recomputing only the cells around a landmark that moved.

use super::config::MapConfig;
use super::stamp::{Rings, Shape, Stamp};
use crate::geometry::Point2;
use crate::perception::markers::MarkerCategory;
use std::collections::BTreeMap;

/// Landmark positions as last stamped, their stamps and the resulting costs.
#[derive(Clone, Debug, Default)]
pub struct LandmarkLayer {
    positions: BTreeMap<u32, Point2>,
    stamps: Vec<Stamp>,
}

impl LandmarkLayer {
    pub fn stamps(&self) -> &[Stamp] {
        &self.stamps
    }

    /// Takes the filter's landmark means; returns the stamps that appeared or went away,
    /// whose areas need recomputing. A landmark that moved less than `min_move` is left.
    pub fn update(
        &mut self,
        estimates: impl IntoIterator<Item = (u32, Point2)>,
        config: &MapConfig,
        min_move: f64,
    ) -> Vec<Stamp> {
        let mut changed = false;
        for (id, p) in estimates {
            match self.positions.get_mut(&id) {
                Some(old) if old.distance(p) < min_move => {}
                Some(old) => {
                    *old = p;
                    changed = true;
                }
                None => {
                    self.positions.insert(id, p);
                    changed = true;
                }
            }
        }
        if !changed {
            return Vec::new();
        }
        self.restamp(config)
    }

    /// Drops landmarks the filter no longer holds (a block put down elsewhere); returns
    /// the stamps that went away.
    pub fn remove(&mut self, ids: &[u32], config: &MapConfig) -> Vec<Stamp> {
        let before = self.positions.len();
        self.positions.retain(|id, _| !ids.contains(id));
        if self.positions.len() == before {
            return Vec::new();
        }
        self.restamp(config)
    }

    /// The stamps for the positions now held; returns those that appeared or went away.
    fn restamp(&mut self, config: &MapConfig) -> Vec<Stamp> {
        let fresh = stamps_for(&self.positions, config);
        let mut dirty: Vec<Stamp> = self
            .stamps
            .iter()
            .filter(|s| !fresh.contains(s))
            .copied()
            .collect();
        dirty.extend(fresh.iter().filter(|s| !self.stamps.contains(s)).copied());
        self.stamps = fresh;
        dirty
    }
}

/// Rings by marker category: walls and obstacles at seed 001's 0.30 m (gates too, navdeck's
/// choice), blocks at its 0.25 m.
pub fn rings_for(id: u32, config: &MapConfig) -> Rings {
    let block = matches!(
        MarkerCategory::of(id),
        MarkerCategory::RedBlock | MarkerCategory::BlueBlock
    );
    if block {
        Rings {
            lethal: config.block_lethal_radius,
            inflated: config.block_inflation,
            gradient: config.gradient,
        }
    } else {
        Rings {
            lethal: config.lethal_radius,
            inflated: config.obstacle_inflation,
            gradient: config.gradient,
        }
    }
}

/// A disc per landmark, and a wall between boundary markers with consecutive IDs.
fn stamps_for(positions: &BTreeMap<u32, Point2>, config: &MapConfig) -> Vec<Stamp> {
    let mut stamps = Vec::with_capacity(positions.len() * 2);
    for (&id, &p) in positions {
        let rings = rings_for(id, config);
        stamps.push(Stamp {
            shape: Shape::Disc(p),
            rings,
        });
        let is_wall = |id: u32| MarkerCategory::of(id) == MarkerCategory::Boundary;
        if is_wall(id)
            && is_wall(id + 1)
            && let Some(&next) = positions.get(&(id + 1))
            && p.distance(next) <= config.wall_join
        {
            stamps.push(Stamp {
                shape: Shape::Wall(p, next),
                rings,
            });
        }
    }
    stamps
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn neighbouring_boundary_markers_make_a_wall_far_ones_do_not() {
        let config = MapConfig::default();
        let mut layer = LandmarkLayer::default();
        let dirty = layer.update(
            [
                (1, Point2::new(0.0, 0.0)),
                (2, Point2::new(0.5, 0.0)),
                (3, Point2::new(2.0, 0.0)),
                (301, Point2::new(1.0, 1.0)),
            ],
            &config,
            0.01,
        );
        let walls = layer
            .stamps()
            .iter()
            .filter(|s| matches!(s.shape, Shape::Wall(..)))
            .count();
        assert_eq!(walls, 1, "only 1-2 are close enough to join");
        assert_eq!(dirty.len(), 5);
    }

    #[test]
    fn only_a_moved_landmark_dirties_the_layer() {
        let config = MapConfig::default();
        let mut layer = LandmarkLayer::default();
        layer.update([(301, Point2::new(0.0, 0.0))], &config, 0.01);
        assert!(
            layer
                .update([(301, Point2::new(0.004, 0.0))], &config, 0.01)
                .is_empty()
        );
        let dirty = layer.update([(301, Point2::new(0.2, 0.0))], &config, 0.01);
        assert_eq!(dirty.len(), 2, "old and new disc");
        let dirty = layer.remove(&[301], &config);
        assert_eq!(
            dirty.len(),
            1,
            "a landmark the filter dropped takes its disc away"
        );
        assert!(layer.stamps().is_empty());
    }
}
