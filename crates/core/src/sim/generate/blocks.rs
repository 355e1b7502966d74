//! Blocks in open floor, of the colours drawn for them, and the robot's start.

use super::draft::Draft;
use super::draw::{heading, pick};
use super::rules::{GATE_KEEP_OUT, MIN_BLOCK_SPACING, START_CLEARANCE, TRIES, WALL_CLEARANCE};
use crate::geometry::{Point2, Pose2};
use crate::sim::{Block, BlockColor, DEFAULT_BLOCK_SIZE};
use rand_chacha::ChaCha8Rng;

/// First red and blue block ids (seed 001 section 1: red 421-450, blue 521-550), odd, each
/// block taking the odd id and the next.
const FIRST_RED: u32 = 421;
const FIRST_BLUE: u32 = 521;

/// Places a block of each of `colours`, in turn.
pub fn place(d: &mut Draft, rng: &mut ChaCha8Rng, colours: &[BlockColor]) -> Result<(), String> {
    let count = colours.len();
    for (i, &color) in colours.iter().enumerate() {
        let first = match color {
            BlockColor::Red => FIRST_RED,
            BlockColor::Blue => FIRST_BLUE,
        };
        let before = colours[..i].iter().filter(|&&c| c == color).count();
        let odd = first + 2 * before as u32;
        let spot = open_spot(d, rng, WALL_CLEARANCE, MIN_BLOCK_SPACING);
        let Some(p) = spot else {
            return Err(format!(
                "no place for block {} of {count} {WALL_CLEARANCE} m from every wall and box and {MIN_BLOCK_SPACING} m from the other blocks",
                i + 1
            ));
        };
        d.world.blocks.push(Block {
            color,
            pose: Pose2::new(p.x, p.y, heading(rng)),
            size: DEFAULT_BLOCK_SIZE,
            markers: [odd, odd + 1],
        });
    }
    Ok(())
}

/// A start pose in open floor, clear of the blocks.
pub fn start(d: &mut Draft, rng: &mut ChaCha8Rng) -> Result<(), String> {
    let spot = open_spot(d, rng, START_CLEARANCE, WALL_CLEARANCE);
    let Some(p) = spot else {
        return Err(format!(
            "no start {START_CLEARANCE} m from every wall and box and {WALL_CLEARANCE} m from the blocks"
        ));
    };
    d.world.start = Pose2::new(p.x, p.y, heading(rng));
    Ok(())
}

/// Within `TRIES` draws, an open point (see `open_point`) at least `apart` from every
/// block placed so far.
fn open_spot(d: &Draft, rng: &mut ChaCha8Rng, clearance: f64, apart: f64) -> Option<Point2> {
    (0..TRIES).find_map(|_| {
        let p = open_point(d, rng, clearance)?;
        let blocks = &d.world.blocks;
        (blocks
            .iter()
            .all(|b| b.pose.position().distance(p) >= apart))
        .then_some(p)
    })
}

/// A point on a centimetre grid `clearance` from every wall and box, out of the gate lanes.
fn open_point(d: &Draft, rng: &mut ChaCha8Rng, clearance: f64) -> Option<Point2> {
    let (hw, hh) = (d.world.width / 2.0, d.world.height / 2.0);
    let x = pick(rng, -hw + clearance, hw - clearance, 0.01)?;
    let y = pick(rng, -hh + clearance, hh - clearance, 0.01)?;
    let p = Point2::new(x, y);
    (d.clearance(p) >= clearance && d.lane_distance(p) >= GATE_KEEP_OUT).then_some(p)
}
