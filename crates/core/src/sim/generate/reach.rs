//! Can the robot get everywhere the mission needs? The world rasterised, every cell near a
//! wall or box closed to the robot's centre, then a flood fill from the start must reach
//! each block's approach ring and each gate's drop places.

use super::rules::{DROP_STAGING, REACH_RADIUS, REACH_RESOLUTION, STAGING, drop_places};
use crate::geometry::Point2;
use crate::map::grid::OCCUPIED;
use crate::sim::World;
use std::collections::VecDeque;

/// Points on a block's approach ring that must be reachable.
const RING_POINTS: usize = 8;

/// `Ok` when the start, every block's approach ring (`STAGING` round it) and every gate's
/// first drop places lie in one region the robot's centre can move through; else which
/// one is cut off.
pub fn check(world: &World) -> Result<(), String> {
    let open = Open::new(world);
    let start = world.start.position();
    let reached = open
        .fill(start)
        .ok_or_else(|| format!("the start {} is too close to a wall or box", at(start)))?;
    let reachable = |p: Point2| open.cell(p).is_some_and(|k| reached[k]);
    for b in &world.blocks {
        let c = b.pose.position();
        let ring = (0..RING_POINTS).map(|k| {
            let a = k as f64 * std::f64::consts::TAU / RING_POINTS as f64;
            Point2::new(c.x + STAGING * a.cos(), c.y + STAGING * a.sin())
        });
        if let Some(p) = std::iter::once(c).chain(ring).find(|&p| !reachable(p)) {
            return Err(format!(
                "{} block {} at {}: {} cannot be reached from the start",
                b.color.label(),
                b.markers[0],
                at(c),
                at(p)
            ));
        }
    }
    for g in &world.gates {
        let Some(pose) = world.gate_pose(g) else {
            return Err(format!("{} gate has no markers", g.color.label()));
        };
        let (s, c) = pose.theta.sin_cos();
        // The staging point of every drop place the gate's blocks use.
        let count = world.blocks.iter().filter(|b| b.color == g.color).count();
        for place in drop_places(count) {
            let (across, out) = (place.across, DROP_STAGING + place.extra);
            let p = Point2::new(pose.x + c * out - s * across, pose.y + s * out + c * across);
            if !reachable(p) {
                return Err(format!(
                    "{} gate's drop place {} cannot be reached from the start",
                    g.color.label(),
                    at(p)
                ));
            }
        }
    }
    Ok(())
}

/// The cells open to the robot's centre.
struct Open {
    width: usize,
    height: usize,
    origin: Point2,
    open: Vec<bool>,
}

impl Open {
    fn new(world: &World) -> Open {
        let grid = world.rasterize(REACH_RESOLUTION);
        let (width, height) = (grid.width, grid.height);
        let mut open = vec![true; width * height];
        let r = (REACH_RADIUS / REACH_RESOLUTION).ceil() as i64;
        let r2 = (REACH_RADIUS / REACH_RESOLUTION).powi(2);
        let disc: Vec<(i64, i64)> = (-r..=r)
            .flat_map(|dy| (-r..=r).map(move |dx| (dx, dy)))
            .filter(|&(dx, dy)| (dx * dx + dy * dy) as f64 <= r2)
            .collect();
        for y in 0..height {
            for x in 0..width {
                if grid.get(x, y) != OCCUPIED {
                    continue;
                }
                for &(dx, dy) in &disc {
                    let (cx, cy) = (x as i64 + dx, y as i64 + dy);
                    if (0..width as i64).contains(&cx) && (0..height as i64).contains(&cy) {
                        open[cy as usize * width + cx as usize] = false;
                    }
                }
            }
        }
        Open {
            width,
            height,
            origin: grid.origin,
            open,
        }
    }

    /// Index of the open cell holding `p`, if it is open.
    fn cell(&self, p: Point2) -> Option<usize> {
        let fx = ((p.x - self.origin.x) / REACH_RESOLUTION).floor();
        let fy = ((p.y - self.origin.y) / REACH_RESOLUTION).floor();
        let inside =
            (0.0..self.width as f64).contains(&fx) && (0.0..self.height as f64).contains(&fy);
        let k = inside.then(|| fy as usize * self.width + fx as usize)?;
        self.open[k].then_some(k)
    }

    /// Open cells 4-connected to `from`'s; `None` when `from` is not open.
    fn fill(&self, from: Point2) -> Option<Vec<bool>> {
        let first = self.cell(from)?;
        let mut seen = vec![false; self.open.len()];
        seen[first] = true;
        let mut queue = VecDeque::from([first]);
        while let Some(k) = queue.pop_front() {
            let (x, y) = (k % self.width, k / self.width);
            let neighbours = [
                (x > 0).then(|| k - 1),
                (x + 1 < self.width).then(|| k + 1),
                (y > 0).then(|| k - self.width),
                (y + 1 < self.height).then(|| k + self.width),
            ];
            for n in neighbours.into_iter().flatten() {
                if self.open[n] && !seen[n] {
                    seen[n] = true;
                    queue.push_back(n);
                }
            }
        }
        Some(seen)
    }
}

fn at(p: Point2) -> String {
    format!("({:.2}, {:.2})", p.x, p.y)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    #[test]
    fn the_arena_is_reachable_and_a_walled_garden_is_not() {
        check(&World::default_arena()).unwrap();
        let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
        let mut garden = World::load(&root.join("tests/worlds/walled_garden.toml")).unwrap();
        check(&garden).unwrap();
        // A block inside the closed room, out of the start's reach.
        let mut block = World::default_arena().blocks[0].clone();
        block.pose = crate::geometry::Pose2::new(0.9, 0.9, 0.0);
        garden.blocks.push(block);
        let err = check(&garden).unwrap_err();
        assert!(err.contains("cannot be reached"), "{err}");
    }
}
