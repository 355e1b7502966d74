//! What one robot of a fleet has explored, for the others: the cells its lidar mapped
//! and the places its camera looked at, in the fleet's one frame (twins start at known
//! poses in one world). Another robot's exploration takes them as explored too: a
//! frontier whose unknown side another robot mapped is no frontier, and space another
//! robot's camera looked at is no unseen space. Its own map is left as it is: the
//! others' cells steer only the choice of where to explore.

use super::coverage::Coverage;
use crate::geometry::Point2;
use crate::map::costmap::{Costmap, NO_INFORMATION};

/// One robot's explored space, as the fleet passes it to the others.
#[derive(Clone, Debug, Default)]
pub struct ExploredLayer {
    origin: Point2,
    resolution: f64,
    width: usize,
    height: usize,
    /// Map cells the lidar has mapped (anything but unknown).
    mapped: Vec<bool>,
    /// What the camera looked at.
    seen: Coverage,
}

impl ExploredLayer {
    /// The layer of a robot whose planning map is `map` and whose camera looked at
    /// `seen`.
    pub fn new(map: &Costmap, seen: &Coverage) -> Self {
        let mapped = (0..map.width * map.height)
            .map(|i| map.get(i % map.width, i / map.width) != NO_INFORMATION)
            .collect();
        Self {
            origin: map.origin,
            resolution: map.resolution,
            width: map.width,
            height: map.height,
            mapped,
            seen: seen.clone(),
        }
    }

    /// Whether the lidar mapped the cell holding `p`.
    pub fn mapped(&self, p: Point2) -> bool {
        if self.resolution <= 0.0 {
            return false;
        }
        let (fx, fy) = (
            (p.x - self.origin.x) / self.resolution,
            (p.y - self.origin.y) / self.resolution,
        );
        let inside = fx >= 0.0 && fy >= 0.0 && fx < self.width as f64 && fy < self.height as f64;
        inside && self.mapped[fy as usize * self.width + fx as usize]
    }

    /// Whether the camera looked at `p`.
    pub fn seen(&self, p: Point2) -> bool {
        self.seen.was_seen(p)
    }
}

/// Whether any of `layers` mapped `p`.
pub fn mapped_by(layers: &[std::sync::Arc<ExploredLayer>], p: Point2) -> bool {
    layers.iter().any(|l| l.mapped(p))
}

/// Whether any of `layers` looked at `p`.
pub fn seen_by(layers: &[std::sync::Arc<ExploredLayer>], p: Point2) -> bool {
    layers.iter().any(|l| l.seen(p))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Pose2;
    use crate::map::costmap::FREE;

    #[test]
    fn a_layer_answers_what_its_robot_mapped_and_looked_at_in_the_shared_frame() {
        // 2 m x 1 m at 0.1 m from (-1, 0): the west half mapped, the east half unknown.
        let mut map = Costmap::new(20, 10, 0.1, Point2::new(-1.0, 0.0), NO_INFORMATION);
        for y in 0..10 {
            for x in 0..10 {
                map.set(x, y, FREE);
            }
        }
        let mut seen = Coverage::default();
        seen.look(&map, Pose2::new(-0.5, 0.5, 0.0), 0.3, 1.0);
        let layer = ExploredLayer::new(&map, &seen);
        assert!(layer.mapped(Point2::new(-0.95, 0.05)));
        assert!(!layer.mapped(Point2::new(0.5, 0.5)), "the unknown half");
        assert!(!layer.mapped(Point2::new(-1.5, 0.5)), "outside the map");
        assert!(layer.seen(Point2::new(-0.35, 0.5)));
        assert!(!layer.seen(Point2::new(-0.9, 0.9)));
        let layers = [std::sync::Arc::new(layer)];
        assert!(mapped_by(&layers, Point2::new(-0.5, 0.5)));
        assert!(!seen_by(&[], Point2::new(-0.35, 0.5)));
    }
}
