//! The red and the blue gate: each on the boundary midway between two boundary markers
//! (as maps/arena.toml places its gates), with a clear lane in front for its drops.

use super::draft::{Draft, Slot};
use super::rules::{DROP_DISTANCE, DROP_ROW, DROP_STAGING, GATE_CLEARANCE, TRIES};
use crate::geometry::{Point2, Segment};
use crate::sim::BlockColor;
use crate::sim::shapes::segment_distance2;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// Red gate ids (seed 001 section 1: 401-420); the mission pairs an odd id with the next.
const RED_GATE: [u32; 2] = [401, 402];
/// Blue gate ids (seed 001 section 1: 501-520).
const BLUE_GATE: [u32; 2] = [501, 502];
/// The two gates' lanes keep this far apart, metres, so one gate's markers never sit
/// among the other's and blocks dropped at one are not in the way to the other.
const GATE_SPACING: f64 = 1.0;
/// The lane reaches this far past the robot centre at the furthest drop place, metres
/// (the 0.08 m body and a margin).
const LANE_BEYOND: f64 = 0.15;

/// Places both gates; `blocks` is the block count, which sets how deep the lanes are.
pub fn place(d: &mut Draft, rng: &mut ChaCha8Rng, blocks: usize) -> Result<(), String> {
    let reds = blocks.div_ceil(2);
    let blues = blocks / 2;
    for (color, ids, count) in [
        (BlockColor::Red, RED_GATE, reds),
        (BlockColor::Blue, BLUE_GATE, blues),
    ] {
        // Drop places come in rows of two, each row DROP_ROW further out.
        let rows = count.max(1).div_ceil(2);
        let depth = DROP_STAGING + DROP_ROW * (rows - 1) as f64 + LANE_BEYOND;
        let chosen = (0..TRIES).find_map(|_| {
            let slot = d.slots[rng.random_range(0..d.slots.len())];
            let lane = Segment::new(ahead(slot, DROP_DISTANCE), ahead(slot, depth));
            let clear = d.segment_clearance(lane, Some(slot.wall)) >= GATE_CLEARANCE;
            let apart = d
                .lanes
                .iter()
                .all(|o| segment_distance2(lane.a, lane.b, *o) >= GATE_SPACING.powi(2));
            (clear && apart).then_some((slot, lane))
        });
        let Some((slot, lane)) = chosen else {
            return Err(format!(
                "no place on the boundary for the {} gate with a clear lane {depth:.2} m deep",
                color.label()
            ));
        };
        d.add_gate(color, ids, slot);
        d.lanes.push(lane);
    }
    Ok(())
}

/// The point `distance` in front of a slot.
pub fn ahead(slot: Slot, distance: f64) -> Point2 {
    let (s, c) = slot.normal.sin_cos();
    Point2::new(slot.at.x + c * distance, slot.at.y + s * distance)
}
