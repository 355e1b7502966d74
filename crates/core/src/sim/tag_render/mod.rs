//! The twin's tag camera as a picture (seed 003 §1.2.2, §2.1): what the grey camera of
//! `TagCameraConfig` sees of a tag map's floor from a robot pose, each tag painted as its
//! AprilTag 36h11 pattern (the cells come from OpenCV's dictionary, handed in by the
//! caller), lying square to its zone's way with the marker's top facing it.
//!
//! The floor is plain light grey with a speckle fixed to it and uneven light (`floor`);
//! each pixel's ray meets the floor through the pinhole (`projection`); tags are painted
//! over it with their edges anti-aliased (`paint`); noise goes on last. Simplifications:
//! no lens distortion, no motion blur, nothing on the floor but the tags.

mod floor;
mod paint;
mod projection;

pub use paint::{FloorTag, MARKER_CELLS, TagCells};

use crate::geometry::Pose2;
use crate::perception::frame::GrayFrame;
use crate::perception::intrinsics::Intrinsics;
use crate::perception::mount::Mount;
use crate::perception::tag_camera::TagCameraConfig;
use crate::sim::noise_bank::NoiseBank;
use crate::tags::{TagId, TagMap};
use floor::{FloorShade, FrameLight, noise_bank};
use paint::{Canvas, InkLevels};
use projection::FloorView;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use std::collections::BTreeMap;

/// Grey levels of a tag's printed black and white under full light.
const INK: InkLevels = InkLevels {
    black: 30.0,
    white: 222.0,
};
/// Grey of whatever a ray meets above the floor's horizon.
const ABOVE_FLOOR: u8 = 90;

/// Renders the tag camera's frames of one tag map.
#[derive(Clone, Debug)]
pub struct TagRenderer {
    intrinsics: Intrinsics,
    mount: Mount,
    tags: Vec<FloorTag>,
    /// Tags of the map with no pattern to paint (ids outside the dictionary).
    unpainted: Vec<TagId>,
    /// A cell's width on the floor, metres.
    cell: f64,
    shade: FloorShade,
    noise: NoiseBank,
}

impl TagRenderer {
    /// A renderer of `map`'s floor seen by `camera`, each tag's black square `side`
    /// metres across and painted with its cells from `patterns`; `seed` fixes the
    /// floor's speckle, its light and the noise bank.
    pub fn new(
        map: &TagMap,
        camera: &TagCameraConfig,
        side: f64,
        patterns: &BTreeMap<TagId, TagCells>,
        seed: u64,
    ) -> Self {
        let mut tags = Vec::new();
        let mut unpainted = Vec::new();
        for (&id, tag) in &map.tags {
            match patterns.get(&id) {
                Some(cells) => {
                    let heading = tag.zone.heading();
                    tags.push(FloorTag {
                        id,
                        centre: [tag.x, tag.y],
                        up: [heading.cos(), heading.sin()],
                        cells: *cells,
                    });
                }
                None => unpainted.push(id),
            }
        }
        let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x7a6_f100);
        let k = camera.intrinsics();
        // Two frames' worth of noise, so consecutive frames' offsets differ.
        let pixels = k.width as usize * k.height as usize;
        Self {
            shade: FloorShade::new(&mut rng),
            noise: noise_bank(camera.noise_std, 2 * pixels, &mut rng),
            intrinsics: k,
            mount: camera.mount(),
            tags,
            unpainted,
            cell: side / MARKER_CELLS as f64,
        }
    }

    pub fn intrinsics(&self) -> &Intrinsics {
        &self.intrinsics
    }

    /// Tags of the map that cannot be painted (no 36h11 pattern for their id).
    pub fn unpainted(&self) -> &[TagId] {
        &self.unpainted
    }

    /// The side of a tag's black square, metres.
    pub fn side(&self) -> f64 {
        self.cell * MARKER_CELLS as f64
    }

    /// The tags whose black square lies wholly inside the image from `pose`, at least
    /// `margin` pixels from its edges: those a detector should find.
    pub fn wholly_in_view(&self, pose: Pose2, margin: f64) -> Vec<TagId> {
        let view = FloorView::new(&self.intrinsics, &self.mount, pose);
        let (w, h) = (view.width() as f64, view.height() as f64);
        let inside = |(u, v): (f64, f64)| {
            u >= margin && v >= margin && u <= w - 1.0 - margin && v <= h - 1.0 - margin
        };
        (self.tags.iter())
            .filter(|t| {
                (t.marker_corners(self.cell).iter())
                    .all(|&[x, y]| view.pixel_of(x, y).is_some_and(inside))
            })
            .map(|t| t.id)
            .collect()
    }

    /// The frame seen from `pose`, its noise placed by `rng`.
    pub fn render(&self, pose: Pose2, rng: &mut ChaCha8Rng) -> GrayFrame {
        let view = FloorView::new(&self.intrinsics, &self.mount, pose);
        let (w, h) = (view.width(), view.height());
        let centre = view.floor_at(w as f64 / 2.0, h as f64 / 2.0);
        let light_at = |u: usize, v: usize| {
            let p = view.floor_at(u as f64, v as f64).or(centre);
            p.map_or(1.0, |p| self.shade.light(p))
        };
        let light = FrameLight::new(
            [
                light_at(0, 0),
                light_at(w - 1, 0),
                light_at(0, h - 1),
                light_at(w - 1, h - 1),
            ],
            w,
            h,
        );
        let mut data = vec![0u8; w * h];
        data.par_chunks_mut(w).enumerate().for_each(|(v, row)| {
            let vf = v as f32;
            if let Some((start, step)) = view.row_on_floor(v as f64) {
                self.shade.paint_row(start, step, &light, vf, row);
                return;
            }
            for (u, pixel) in row.iter_mut().enumerate() {
                *pixel = match view.floor_at(u as f64, v as f64) {
                    // A cast saturates: rounded to the nearest level and held to 0..=255.
                    Some(p) => (self.shade.grey(p) * light.at(u as f32, vf) + 0.5) as u8,
                    None => ABOVE_FLOOR,
                };
            }
        });
        let canvas = Canvas {
            view: &view,
            light: &light,
            shade: &self.shade,
            levels: INK,
            cell: self.cell,
        };
        for tag in &self.tags {
            canvas.paint(tag, &mut data);
        }
        self.noise.add(&mut data, rng);
        GrayFrame {
            width: w,
            height: h,
            data,
        }
    }
}

#[cfg(test)]
mod tests;
