//! What the camera has looked at: a coarse grid over the planning map, marked wherever
//! the camera's view cone reached with a clear line of sight. Blocks are found only by
//! seeing their markers, so exploration is complete when every free place the robot can
//! reach has been in view, not when the lidar map has no unknown cells left (a lidar maps
//! a small room in seconds, long before the camera has looked everywhere).

use super::clusters::{clusters, nearest_centroid};
use crate::geometry::{Point2, Pose2, wrap_angle};
use crate::map::costmap::{Costmap, INFLATED, NO_INFORMATION, is_lethal};

/// Side of a coverage cell, metres: about a block's footprint with its staging margin.
pub const CELL: f64 = 0.1;

/// Cells seen, over the planning map's extent.
#[derive(Clone, Debug, Default)]
pub struct Coverage {
    origin: Point2,
    width: usize,
    height: usize,
    seen: Vec<bool>,
}

/// A run of free cells not yet seen, and where to stand to look at it.
#[derive(Clone, Debug, PartialEq)]
pub struct Unseen {
    pub target: Point2,
    pub cells: usize,
}

impl Coverage {
    /// Marks the cells within `range` and half of `fov` (radians) of `pose` whose centre
    /// the map does not hide behind a lethal cell.
    pub fn look(&mut self, map: &Costmap, pose: Pose2, range: f64, fov: f64) {
        self.fit(map);
        let reach = (range / CELL).ceil() as i64;
        let Some((cx, cy)) = self.cell_of(pose.position()) else {
            return;
        };
        for dy in -reach..=reach {
            for dx in -reach..=reach {
                let (x, y) = (cx as i64 + dx, cy as i64 + dy);
                if x < 0 || y < 0 || x >= self.width as i64 || y >= self.height as i64 {
                    continue;
                }
                let (x, y) = (x as usize, y as usize);
                if self.seen[y * self.width + x] {
                    continue;
                }
                let c = self.center(x, y);
                let (ddx, ddy) = (c.x - pose.x, c.y - pose.y);
                let d = ddx.hypot(ddy);
                let inside = d <= range
                    && (d < CELL || wrap_angle(ddy.atan2(ddx) - pose.theta).abs() <= fov / 2.0);
                if inside && clear_line(map, pose.position(), c) {
                    self.seen[y * self.width + x] = true;
                }
            }
        }
    }

    /// Clusters (8-connected) of at least `min_cells` free cells (outside the 0.7 ring) not
    /// yet seen that the robot can reach (`reach`, from `targets::reachable` on the same
    /// map), each with the
    /// reachable cell nearest its centroid as the place to go and look, leaving out cells
    /// within `keep_off` of an `avoid` point (places already tried). A cell that
    /// `seen_elsewhere` says was looked at (by another robot of a fleet) counts as seen.
    pub fn unseen(
        &self,
        map: &Costmap,
        reach: &[bool],
        min_cells: usize,
        (avoid, keep_off): (&[Point2], f64),
        seen_elsewhere: impl Fn(Point2) -> bool,
    ) -> Vec<Unseen> {
        if self.seen.is_empty() {
            return Vec::new();
        }
        let (w, h) = (self.width, self.height);
        let reachable = |x: usize, y: usize| {
            map.cell_of(self.center(x, y))
                .is_some_and(|(mx, my)| reach[map.index(mx, my)] && map.get(mx, my) < INFLATED)
        };
        let open = |x: usize, y: usize| {
            !self.seen[y * w + x] && reachable(x, y) && !seen_elsewhere(self.center(x, y))
        };
        let allowed = |&(x, y): &(usize, usize)| {
            let c = self.center(x, y);
            avoid.iter().all(|a| a.distance(c) >= keep_off)
        };
        (clusters(w, h, open).into_iter())
            .filter(|cluster| cluster.len() >= min_cells)
            .filter_map(|cluster| {
                let (tx, ty) = nearest_centroid(&cluster, allowed)?;
                Some(Unseen {
                    target: self.center(tx, ty),
                    cells: cluster.len(),
                })
            })
            .collect()
    }

    /// Whether the camera has looked at `p`.
    pub fn was_seen(&self, p: Point2) -> bool {
        self.cell_of(p)
            .is_some_and(|(x, y)| self.seen[y * self.width + x])
    }

    /// Sizes the grid to the map the first time (the map's extent does not change).
    fn fit(&mut self, map: &Costmap) {
        if !self.seen.is_empty() {
            return;
        }
        let w = (map.width as f64 * map.resolution / CELL).ceil() as usize;
        let h = (map.height as f64 * map.resolution / CELL).ceil() as usize;
        *self = Self {
            origin: map.origin,
            width: w.max(1),
            height: h.max(1),
            seen: vec![false; w.max(1) * h.max(1)],
        };
    }

    fn cell_of(&self, p: Point2) -> Option<(usize, usize)> {
        let (fx, fy) = ((p.x - self.origin.x) / CELL, (p.y - self.origin.y) / CELL);
        let inside = fx >= 0.0 && fy >= 0.0 && fx < self.width as f64 && fy < self.height as f64;
        inside.then_some((fx as usize, fy as usize))
    }

    fn center(&self, x: usize, y: usize) -> Point2 {
        Point2::new(
            self.origin.x + (x as f64 + 0.5) * CELL,
            self.origin.y + (y as f64 + 0.5) * CELL,
        )
    }
}

/// Whether the segment from `a` to `b` crosses no lethal map cell, sampled at half the
/// map's resolution; unknown cells do not hide what lies behind them from a camera, but
/// they do here, because nothing can be said to have been seen through them.
fn clear_line(map: &Costmap, a: Point2, b: Point2) -> bool {
    let d = a.distance(b);
    let steps = (d / (0.5 * map.resolution)).ceil().max(1.0) as usize;
    // The last sample stops short of the target: a cell holding a wall face is seen.
    (1..steps).all(|i| {
        let f = i as f64 / steps as f64;
        let c = map.at(Point2::new(a.x + f * (b.x - a.x), a.y + f * (b.y - a.y)));
        !is_lethal(c) && c != NO_INFORMATION
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::costmap::{FREE, LETHAL};

    /// 3 m x 2 m of free map at 5 cm, with a wall at x = 1.5 m from y = 0 to 1.5 m.
    fn map_with_wall() -> Costmap {
        let mut map = Costmap::new(60, 40, 0.05, Point2::new(0.0, 0.0), FREE);
        for y in 0..30 {
            map.set(30, y, LETHAL);
        }
        map
    }

    fn reach_all(map: &Costmap) -> Vec<bool> {
        (0..map.width * map.height)
            .map(|i| map.get(i % map.width, i / map.width) != LETHAL)
            .collect()
    }

    #[test]
    fn the_view_cone_marks_what_is_ahead_within_range_and_not_behind_a_wall() {
        let map = map_with_wall();
        let mut seen = Coverage::default();
        seen.look(&map, Pose2::new(0.5, 0.5, 0.0), 1.5, 60f64.to_radians());
        assert!(seen.was_seen(Point2::new(1.2, 0.5)), "ahead, in range");
        assert!(!seen.was_seen(Point2::new(0.2, 0.5)), "behind the camera");
        assert!(!seen.was_seen(Point2::new(1.9, 0.5)), "behind the wall");
        assert!(!seen.was_seen(Point2::new(0.5, 1.5)), "outside the cone");
    }

    #[test]
    fn a_full_turn_leaves_only_what_the_wall_hides_and_what_is_out_of_range() {
        let map = map_with_wall();
        let reach = reach_all(&map);
        let mut seen = Coverage::default();
        for k in 0..36 {
            let heading = f64::from(k) * 10f64.to_radians();
            seen.look(
                &map,
                Pose2::new(0.75, 0.75, heading),
                1.5,
                60f64.to_radians(),
            );
        }
        let left = seen.unseen(&map, &reach, 4, (&[], 0.0), |_| false);
        assert!(!left.is_empty());
        assert!(
            left.iter()
                .all(|u| u.target.x > 1.5 || u.target.distance(Point2::new(0.75, 0.75)) > 1.4),
            "{left:?}"
        );
        // Looking from beyond the wall's end covers the rest.
        for (x, y) in [(2.25, 1.0), (2.25, 0.5), (0.75, 1.75)] {
            for k in 0..36 {
                let heading = f64::from(k) * 10f64.to_radians();
                seen.look(&map, Pose2::new(x, y, heading), 1.5, 60f64.to_radians());
            }
        }
        assert!(
            seen.unseen(&map, &reach, 4, (&[], 0.0), |_| false)
                .is_empty()
        );
    }

    #[test]
    fn space_the_robot_cannot_reach_is_never_a_target() {
        let map = map_with_wall();
        let nowhere = vec![false; map.width * map.height];
        let seen = {
            let mut s = Coverage::default();
            s.look(&map, Pose2::new(0.5, 0.5, 0.0), 0.2, 1.0);
            s
        };
        assert!(
            seen.unseen(&map, &nowhere, 1, (&[], 0.0), |_| false)
                .is_empty()
        );
    }
}
