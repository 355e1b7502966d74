//! The twin's lane camera: what the colour camera of `LaneCameraConfig` sees of a lane
//! track (seed 000 §2-§3) from a robot pose at twin time t, as a BGR frame.
//!
//! The floor is a top-down texture of the lane's tape (`texture`), looked up through each
//! pixel's ray worked out once for the fixed mount (`floor`); the lights, barriers, walls
//! and boxes are flat faces filled with a depth buffer (`objects`, `raster`); the
//! lighting scales reflected colours, lays hard shadows on the floor (`lighting`) and
//! mirrors ceiling lamps in it (`glare`); noise is drawn with the seed and placed by the
//! caller's generator (`noise`).
//! `truth` says which light and barrier a frame truly shows. Colours are chosen in
//! OpenCV's HSV against the seed's thresholds (`palette`). Simplifications: no lens
//! distortion, no motion blur, lamps light nothing round them.

mod floor;
mod glare;
mod lighting;
mod noise;
mod objects;
pub mod palette;
mod raster;
mod scanline;
mod texture;
mod truth;
mod view;

#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_objects;

pub use truth::{BarrierTruth, FrameTruth, LightTruth};

use crate::geometry::{Point2, Pose2, Segment};
use crate::perception::colour::BgrFrame;
use crate::perception::intrinsics::Intrinsics;
use crate::perception::lane_camera::LaneCameraConfig;
use crate::perception::mount::Mount;
use crate::sim::track::{Lighting, TrackScene};
use floor::FloorRays;
use glare::Ceiling;
use noise::NoiseBank;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use raster::{Canvas, Face};
use texture::FloorTexture;
use truth::Occluder;
use view::View;

/// Floor round the track and the walls that the texture covers, metres.
const MARGIN: f64 = 0.5;

/// Renders the lane camera's frames of one track scene.
#[derive(Clone, Debug)]
pub struct TrackRenderer {
    scene: TrackScene,
    walls: Vec<Segment>,
    boxes: Vec<(Pose2, f64, f64)>,
    occluders: Vec<Occluder>,
    intrinsics: Intrinsics,
    mount: Mount,
    rays: FloorRays,
    texture: FloorTexture,
    /// The floor's extent, and the shadows placed on it.
    bounds: (Point2, Point2),
    shadows: Vec<Vec<Point2>>,
    ceiling: Ceiling,
    lighting: Lighting,
    noise: NoiseBank,
    /// Reused from frame to frame.
    inverse_depth: Vec<f32>,
    faces: Vec<Face>,
    /// The floor and its glare as last painted, and the pose and brightness it was painted
    /// for: a robot standing still (at a light or a barrier) sees the same floor.
    floor: Vec<u8>,
    floor_seen: Option<(Pose2, f64)>,
}

impl TrackRenderer {
    /// A renderer of `scene` seen by `camera`. `walls`: the world's wall segments (drawn
    /// as vertical grey walls 0.3 m high; a segment on a box's outline is left to the
    /// box); `boxes`: box obstacles on the floor as (pose, width, depth), drawn as brown
    /// boxes 0.15 m high; `seed` places the shadows and the ceiling lamps and draws the noise.
    pub fn new(
        scene: &TrackScene,
        walls: &[Segment],
        boxes: &[(Pose2, f64, f64)],
        camera: &LaneCameraConfig,
        lighting: Lighting,
        seed: u64,
    ) -> Self {
        let outlines: Vec<Segment> = boxes.iter().flat_map(|&b| box_outline(b)).collect();
        let on_outline = |w: &Segment| {
            outlines.iter().any(|o| {
                let near = |p: Point2, q: Point2| p.distance(q) < 1e-6;
                (near(o.a, w.a) && near(o.b, w.b)) || (near(o.a, w.b) && near(o.b, w.a))
            })
        };
        // The posts stand in a world's walls too; they are drawn as posts, not walls.
        let posts = scene.post_outlines();
        let walls: Vec<Segment> = (walls.iter())
            .filter(|w| !on_outline(w) && !posts.contains(w))
            .copied()
            .collect();
        let occluders = truth::walls(&walls)
            .chain(outlines.iter().map(|&segment| Occluder {
                segment,
                height: objects::BOX_HEIGHT,
            }))
            .collect();
        let bounds = floor_bounds(scene, &walls, &outlines);
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let shadows = lighting::shadows(&mut rng, &scene.track, bounds.0, bounds.1);
        let ceiling = Ceiling::new(&mut rng, bounds.0, bounds.1);
        let noise = noise::bank(&mut rng);
        let texture = floor_texture(scene, bounds, &shadows, lighting.shadows);
        let intrinsics = camera.intrinsics();
        let mount = camera.mount();
        let rays = FloorRays::new(&intrinsics, &mount, texture.cell());
        let pixels = intrinsics.width as usize * intrinsics.height as usize;
        Self {
            scene: scene.clone(),
            walls,
            boxes: boxes.to_vec(),
            occluders,
            intrinsics,
            mount,
            rays,
            texture,
            bounds,
            shadows,
            ceiling,
            lighting,
            noise,
            inverse_depth: vec![0.0; pixels],
            faces: Vec::new(),
            floor: vec![0; 3 * pixels],
            floor_seen: None,
        }
    }

    pub fn lighting(&self) -> Lighting {
        self.lighting
    }

    /// Renders later frames under `lighting` (the shadows stay where the seed put them).
    pub fn set_lighting(&mut self, lighting: Lighting) {
        if lighting.shadows != self.lighting.shadows {
            self.texture = floor_texture(&self.scene, self.bounds, &self.shadows, lighting.shadows);
        }
        self.lighting = lighting;
        self.floor_seen = None;
    }

    /// The frame the camera takes from `pose` at twin time `t`, its noise from `rng`.
    pub fn render(&mut self, pose: Pose2, t: f64, rng: &mut ChaCha8Rng) -> BgrFrame {
        let view = View::new(&self.intrinsics, &self.mount, pose);
        let (width, height) = (view.width, view.height);
        let brightness = self.lighting.level.brightness();
        if self.floor_seen != Some((pose, brightness)) {
            let room = palette::bytes(palette::bgr(palette::ROOM), brightness);
            (self.rays).paint(&self.texture, pose, brightness, room, &mut self.floor);
            if self.lighting.glare {
                (self.ceiling).paint_glare(&self.rays, &view, pose, &mut self.floor);
            }
            self.floor_seen = Some((pose, brightness));
        }
        let mut data = self.floor.clone();
        self.faces.clear();
        objects::faces(
            &self.scene,
            &self.walls,
            &self.boxes,
            t,
            brightness,
            &mut self.faces,
        );
        self.inverse_depth.fill(0.0);
        let mut canvas = Canvas {
            pixels: &mut data,
            inverse_depth: &mut self.inverse_depth,
        };
        for face in &self.faces {
            raster::fill(&mut canvas, &view, face);
        }
        self.noise.add(&mut data, rng);
        BgrFrame {
            width,
            height,
            data,
        }
    }

    /// Ground truth for scoring detection: the light and barrier visibly in the frame
    /// from `pose` at `t` (in front of the camera, inside the image, not hidden behind a
    /// wall), with their true state, range from the lens and apparent size.
    pub fn truth(&self, pose: Pose2, t: f64) -> FrameTruth {
        let view = View::new(&self.intrinsics, &self.mount, pose);
        truth::frame_truth(&self.scene, &self.occluders, &view, t)
    }

    /// The pixel where the world point (`x`, `y`, `z`) appears from `pose`, if it is in
    /// front of the lens (it may lie outside the image).
    pub fn pixel_of(&self, pose: Pose2, x: f64, y: f64, z: f64) -> Option<(f64, f64)> {
        View::new(&self.intrinsics, &self.mount, pose).pixel(nalgebra::Vector3::new(x, y, z))
    }
}

/// The four sides of a box obstacle (pose, width along its x, depth along its y).
fn box_outline((pose, width, depth): (Pose2, f64, f64)) -> [Segment; 4] {
    let (w, d) = (width / 2.0, depth / 2.0);
    let c =
        [(-w, -d), (w, -d), (w, d), (-w, d)].map(|(x, y)| pose.transform_point(Point2::new(x, y)));
    [0, 1, 2, 3].map(|i| Segment::new(c[i], c[(i + 1) % 4]))
}

/// The floor the texture covers: the track and every wall and box, and a margin.
fn floor_bounds(scene: &TrackScene, walls: &[Segment], outlines: &[Segment]) -> (Point2, Point2) {
    let ends = walls.iter().chain(outlines).flat_map(|s| [s.a, s.b]);
    let points = scene.track.points().iter().copied().chain(ends);
    let (mut lo, mut hi) = (
        Point2::new(f64::MAX, f64::MAX),
        Point2::new(f64::MIN, f64::MIN),
    );
    for p in points.filter(|p| p.x.is_finite() && p.y.is_finite()) {
        lo = Point2::new(lo.x.min(p.x), lo.y.min(p.y));
        hi = Point2::new(hi.x.max(p.x), hi.y.max(p.y));
    }
    let m = MARGIN + scene.track.lane_width;
    (
        Point2::new(lo.x - m, lo.y - m),
        Point2::new(hi.x + m, hi.y + m),
    )
}

fn floor_texture(
    scene: &TrackScene,
    bounds: (Point2, Point2),
    shadows: &[Vec<Point2>],
    shadowed: bool,
) -> FloorTexture {
    let shadows = if shadowed { shadows } else { &[] };
    FloorTexture::new(bounds.0, bounds.1, &scene.track, shadows)
}
