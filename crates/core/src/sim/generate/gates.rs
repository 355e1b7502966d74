//! The red and the blue gate: each on the boundary midway between two boundary markers
//! (as maps/arena.toml places its gates), with a clear lane in front for its drops.

use super::draft::{Draft, Slot};
use super::rules::{DROP_DISTANCE, DROP_SLOT, DROP_STAGING, GATE_CLEARANCE, TRIES, drop_places};
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

/// Places both gates; the blocks' `colours` set how deep each gate's lane is.
pub fn place(d: &mut Draft, rng: &mut ChaCha8Rng, colours: &[BlockColor]) -> Result<(), String> {
    let of = |c: BlockColor| colours.iter().filter(|&&b| b == c).count();
    let (reds, blues) = (of(BlockColor::Red), of(BlockColor::Blue));
    for (color, ids, count) in [
        (BlockColor::Red, RED_GATE, reds),
        (BlockColor::Blue, BLUE_GATE, blues),
    ] {
        // The lane runs out to the staging point of the furthest drop place used, and is
        // wider by as much as a drop place used lies further aside than DROP_SLOT.
        let used = drop_places(count);
        let extra = used.iter().map(|p| p.extra).fold(0.0, f64::max);
        let aside = used.iter().map(|p| p.across.abs()).fold(0.0, f64::max);
        let depth = DROP_STAGING + extra + LANE_BEYOND;
        let clearance = GATE_CLEARANCE + (aside - DROP_SLOT).max(0.0);
        let chosen = (0..TRIES).find_map(|_| {
            let slot = d.slots[rng.random_range(0..d.slots.len())];
            let lane = Segment::new(ahead(slot, DROP_DISTANCE), ahead(slot, depth));
            let clear = d.segment_clearance(lane, Some(slot.wall)) >= clearance;
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
