//! A fleet of twins in one world: where each starts, and the board through which each
//! twin learns where the others stand and which blocks they moved or carry. Each twin
//! steps on its own; before a step it reads the board, after it writes back, so a twin
//! sees the others as they stood after their own latest step.

use super::shapes::dist2_to_segment;
use super::{BlockState, Neighbour, Twin, World};
use crate::geometry::{Point2, Pose2};

/// Clearance every spread start keeps from walls and blocks beyond the footprint, metres.
const START_CLEARANCE: f64 = 0.05;
/// Gap between two robots' footprints at spread starts, metres.
const START_GAP: f64 = 0.15;

/// What the fleet's twins share: each robot's pose and radius, and the blocks.
#[derive(Clone, Debug)]
pub struct FleetBoard {
    robots: Vec<Neighbour>,
    blocks: Vec<BlockState>,
    /// Which robot holds each block.
    holders: Vec<Option<usize>>,
}

impl FleetBoard {
    /// A board for robots standing at `starts` with footprint `radius` in `world`.
    pub fn new(world: &World, starts: &[Pose2], radius: f64) -> Self {
        Self {
            robots: (starts.iter())
                .map(|&pose| Neighbour { pose, radius })
                .collect(),
            blocks: world.blocks.iter().map(BlockState::from_block).collect(),
            holders: vec![None; world.blocks.len()],
        }
    }

    pub fn len(&self) -> usize {
        self.robots.len()
    }

    pub fn is_empty(&self) -> bool {
        self.robots.is_empty()
    }

    /// Every robot's pose as last written.
    pub fn poses(&self) -> Vec<Pose2> {
        self.robots.iter().map(|r| r.pose).collect()
    }

    /// Before robot `me` steps: the others stand where they last stood, and the blocks
    /// lie where the fleet last left them.
    pub fn before_step(&self, me: usize, twin: &mut Twin) {
        let others: Vec<Neighbour> = (self.robots.iter().enumerate())
            .filter(|(i, _)| *i != me)
            .map(|(_, r)| *r)
            .collect();
        twin.set_neighbours(&others);
        // A block this robot held at its last step is its own to tell about.
        let shared: Vec<BlockState> = (self.blocks.iter().zip(&self.holders))
            .zip(twin.blocks())
            .map(|((theirs, holder), own)| if *holder == Some(me) { own } else { theirs })
            .cloned()
            .collect();
        twin.adopt_blocks(&shared);
    }

    /// After robot `me` stepped: where it stands, the block it holds, and a block it let
    /// go of (or moved) since.
    pub fn after_step(&mut self, me: usize, twin: &Twin) {
        if let Some(r) = self.robots.get_mut(me) {
            r.pose = twin.pose();
        }
        let held = twin.held_block();
        for (i, own) in twin.blocks().iter().enumerate().take(self.blocks.len()) {
            let was_mine = self.holders[i] == Some(me);
            let free_here = self.holders[i].is_none() && self.blocks[i] != *own;
            if held == Some(i) {
                self.blocks[i] = own.clone();
                self.holders[i] = Some(me);
            } else if was_mine || free_here {
                self.blocks[i] = own.clone();
                self.holders[i] = None;
            }
        }
    }
}

/// Starts for `n` robots of footprint `radius`: the world's start first, then free poses
/// nearest it on a grid of the robots' spacing beside and behind it (ahead only when
/// those run out), all facing the start's way. Each keeps
/// clear of walls, blocks and the others. Fewer than `n` free places: the error says how
/// many fitted.
pub fn spread_starts(world: &World, n: usize, radius: f64) -> Result<Vec<Pose2>, String> {
    let spacing = 2.0 * radius + START_GAP;
    let start = world.start;
    let (c, s) = (start.theta.cos(), start.theta.sin());
    let reach = (world.width.max(world.height) / spacing).ceil() as i32;
    let mut offsets: Vec<(i32, i32)> = (-reach..=reach)
        .flat_map(|i| (-reach..=reach).map(move |j| (i, j)))
        .collect();
    // Beside and behind before ahead, so that the first robots face open floor; then
    // nearest first, left first.
    offsets.sort_by_key(|&(i, j)| (i > 0, i * i + j * j, i, -j));
    let mut starts: Vec<Pose2> = Vec::with_capacity(n);
    for (i, j) in offsets {
        if starts.len() == n {
            break;
        }
        let (dx, dy) = (i as f64 * spacing, j as f64 * spacing);
        let p = Point2::new(start.x + c * dx - s * dy, start.y + s * dx + c * dy);
        if place_is_free(world, p, radius, &starts) {
            starts.push(Pose2::new(p.x, p.y, start.theta));
        }
    }
    if starts.len() < n {
        return Err(format!(
            "room for {} robots of radius {radius} m near the start in world {}, not {n}",
            starts.len(),
            world.name
        ));
    }
    Ok(starts)
}

/// Whether a footprint at `p` stays inside the world and clear of its walls, its blocks
/// and the robots already placed.
fn place_is_free(world: &World, p: Point2, radius: f64, placed: &[Pose2]) -> bool {
    let r = radius + START_CLEARANCE;
    let inside = p.x.abs() + r <= world.width / 2.0 && p.y.abs() + r <= world.height / 2.0;
    inside
        && (world.walls.iter()).all(|w| dist2_to_segment(p, w.a, w.b) >= r * r)
        && (world.blocks.iter())
            .all(|b| p.distance(b.pose.position()) >= r + b.size / std::f64::consts::SQRT_2)
        && (placed.iter()).all(|q| p.distance(q.position()) >= 2.0 * radius + START_GAP - 1e-9)
}

#[cfg(test)]
#[path = "fleet_tests.rs"]
mod tests;
