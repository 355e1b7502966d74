//! Ground truth for scoring a lane pipeline's detections: the traffic light and barrier
//! visibly in a frame, with their true state, range and size in the image.

use super::objects::{WALL_HEIGHT, arm_direction, lamp_centre};
use super::view::View;
use crate::data::{BarrierState, LightColour};
use crate::geometry::{Point2, Segment};
use crate::sim::track::{ARM_HEIGHT, LAMP_RADIUS, TrackScene};
use nalgebra::Vector3;

/// What a frame truly shows.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FrameTruth {
    pub light: Option<LightTruth>,
    pub barrier: Option<BarrierTruth>,
}

/// The nearest traffic light whose lit lamp is in the frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightTruth {
    pub colour: LightColour,
    /// From the lens to the lit lamp's centre, metres.
    pub range: f64,
    /// The lit lamp's radius in the image, pixels.
    pub radius_px: f64,
}

/// The nearest barrier whose arm is in the frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BarrierTruth {
    pub state: BarrierState,
    /// The arm's angle above level, degrees.
    pub angle_deg: f64,
    /// From the lens to the middle of the arm's part in view, metres.
    pub range: f64,
    /// Length of the arm's part in view in the image, pixels.
    pub length_px: f64,
}

/// Points along an arm tested for being in view.
const ARM_SAMPLES: usize = 25;

/// A solid that can hide what is behind it: a vertical face on `segment` of `height`.
#[derive(Clone, Copy, Debug)]
pub struct Occluder {
    pub segment: Segment,
    pub height: f64,
}

/// Whether the line from the lens to `target` passes clear of every occluder: where it
/// crosses one, it must pass above it (its height there by linear interpolation).
pub fn clear(view: &View, target: Vector3<f64>, occluders: &[Occluder]) -> bool {
    let from = Point2::new(view.lens.x, view.lens.y);
    let dir = (target.x - from.x, target.y - from.y);
    occluders
        .iter()
        .all(|o| match o.segment.ray_hit(from, dir) {
            Some(f) if f < 1.0 => view.lens.z + f * (target.z - view.lens.z) >= o.height,
            _ => true,
        })
}

/// What `view` truly shows of `scene` at twin time `t`.
pub fn frame_truth(scene: &TrackScene, occluders: &[Occluder], view: &View, t: f64) -> FrameTruth {
    let visible = |p: Vector3<f64>| {
        view.pixel(p)
            .filter(|&px| view.inside(px) && clear(view, p, occluders))
    };
    let light = scene
        .lights
        .iter()
        .filter_map(|light| {
            let colour = light.cycle.colour_at(t);
            let centre = lamp_centre(light, colour);
            let facing = Vector3::new(light.facing.cos(), light.facing.sin(), 0.0);
            // Seen from behind the lamps' plane, the housing hides them.
            if facing.dot(&(view.lens - centre)) <= 0.0 {
                return None;
            }
            visible(centre)?;
            let range = (view.lens - centre).norm();
            // A disc's apparent radius: f r / distance (pinhole similar triangles).
            Some(LightTruth {
                colour,
                range,
                radius_px: view.fx * LAMP_RADIUS / range,
            })
        })
        .min_by(|a, b| a.range.total_cmp(&b.range));
    let barrier = scene
        .barriers
        .iter()
        .filter_map(|barrier| {
            let angle = barrier.angle_at(t);
            let dir = arm_direction(barrier, angle);
            let pivot = Vector3::new(barrier.pivot.x, barrier.pivot.y, ARM_HEIGHT);
            let seen: Vec<(Vector3<f64>, (f64, f64))> = (0..ARM_SAMPLES)
                .map(|i| pivot + dir * (barrier.span * i as f64 / (ARM_SAMPLES - 1) as f64))
                .filter_map(|p| visible(p).map(|px| (p, px)))
                .collect();
            let (first, last) = (seen.first()?, seen.last()?);
            let middle = (first.0 + last.0) / 2.0;
            Some(BarrierTruth {
                state: barrier.state_at(t),
                angle_deg: angle.to_degrees(),
                range: (view.lens - middle).norm(),
                length_px: (first.1.0 - last.1.0).hypot(first.1.1 - last.1.1),
            })
        })
        .min_by(|a, b| a.range.total_cmp(&b.range));
    FrameTruth { light, barrier }
}

/// The world's walls as occluders of wall height.
pub fn walls(walls: &[Segment]) -> impl Iterator<Item = Occluder> + '_ {
    walls.iter().map(|&segment| Occluder {
        segment,
        height: WALL_HEIGHT,
    })
}
