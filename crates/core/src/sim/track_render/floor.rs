//! The floor pass: where each pixel's ray meets the floor, worked out once in the robot's
//! frame (the camera's mount is fixed), and per frame a rigid move of those points into
//! the world and a look-up in the floor texture.

use super::texture::{FloorTexture, LEVELS};
use crate::geometry::Pose2;
use crate::perception::intrinsics::Intrinsics;
use crate::perception::mount::Mount;
use nalgebra::Vector3;
use rayon::prelude::*;

/// Marks a pixel whose ray never meets the floor (it looks at or above the horizon).
const SKY: u8 = u8::MAX;
/// Footprints under this fraction of the finest cell are sampled bilinearly.
const MAGNIFIED: f64 = 0.5;
/// Floor further than this from the lens is drawn as the coarsest level, metres.
const FAR: f64 = 40.0;
/// Pixels painted as one piece of work when the frame is shared among the cores.
const BAND: usize = 640 * 16;

/// For every pixel, where its ray meets the floor in the robot frame and how to sample
/// the texture there (`FloorTexture::sample`'s code) for the floor it spans.
#[derive(Clone)]
pub struct FloorRays {
    points: Vec<[f32; 2]>,
    levels: Vec<u8>,
}

impl std::fmt::Debug for FloorRays {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let floor = self.levels.iter().filter(|&&l| l != SKY).count();
        write!(
            f,
            "FloorRays {{ {floor} of {} pixels see the floor }}",
            self.levels.len()
        )
    }
}

/// Where the ray through pixel (`u`, `v`) meets the floor, in the robot frame.
fn floor_point(k: &Intrinsics, mount: &Mount, u: f64, v: f64) -> Option<[f64; 2]> {
    // The pixel's ray in the camera frame, r = ((u - cx) / fx, (v - cy) / fy, 1)
    // (the pinhole model inverted, Hartley & Zisserman 6.1), turned into the robot frame.
    let ray = Vector3::new((u - k.cx) / k.fx, (v - k.cy) / k.fy, 1.0);
    let d = mount.rotate_to_robot(ray);
    let lens = mount.to_robot(Vector3::zeros());
    if d.z > -1e-6 {
        return None;
    }
    // The ray lens + s d meets z = 0 at s = -lens_z / d_z.
    let s = -lens.z / d.z;
    let p = lens + s * d;
    let far = (p.x - lens.x).hypot(p.y - lens.y) > FAR;
    let clamp = if far {
        FAR / (p.x - lens.x).hypot(p.y - lens.y)
    } else {
        1.0
    };
    Some([
        lens.x + (p.x - lens.x) * clamp,
        lens.y + (p.y - lens.y) * clamp,
    ])
}

impl FloorRays {
    /// The rays of camera `k` on `mount`, with levels for a texture of finest cell `cell`.
    pub fn new(k: &Intrinsics, mount: &Mount, cell: f64) -> Self {
        let (w, h) = (k.width as usize, k.height as usize);
        let mut points = Vec::with_capacity(w * h);
        let mut levels = Vec::with_capacity(w * h);
        for y in 0..h {
            for x in 0..w {
                let (u, v) = (x as f64, y as f64);
                let Some(p) = floor_point(k, mount, u, v) else {
                    points.push([0.0; 2]);
                    levels.push(SKY);
                    continue;
                };
                // The floor one pixel over, across and down: the pixel's footprint.
                let span = |q: Option<[f64; 2]>| {
                    q.map_or(f64::INFINITY, |q| (q[0] - p[0]).hypot(q[1] - p[1]))
                };
                let footprint = span(floor_point(k, mount, u + 1.0, v)).max(span(floor_point(
                    k,
                    mount,
                    u,
                    v + 1.0,
                )));
                // The level whose cell is nearest the footprint (mipmap selection,
                // Williams 1983: level = log2(footprint / cell)), sampled bilinearly
                // where a cell spans two pixels or more.
                let ratio = footprint / cell;
                let level = ratio.log2().round().clamp(0.0, (LEVELS - 1) as f64) as u8;
                points.push([p[0] as f32, p[1] as f32]);
                levels.push(if ratio < MAGNIFIED { 0 } else { level + 1 });
            }
        }
        Self { points, levels }
    }

    /// Where pixel `i`'s ray meets the floor, in the robot frame; None above the horizon.
    #[inline]
    pub fn point(&self, i: usize) -> Option<[f32; 2]> {
        (self.levels[i] != SKY).then(|| self.points[i])
    }

    /// Paints the floor seen from `pose` into `out` (BGR rows), every colour scaled by
    /// `brightness`; pixels above the horizon get `room`.
    pub fn paint(
        &self,
        texture: &FloorTexture,
        pose: Pose2,
        brightness: f64,
        room: [u8; 3],
        out: &mut [u8],
    ) {
        let (s, c) = pose.theta.sin_cos();
        let (s, c, px, py) = (s as f32, c as f32, pose.x as f32, pose.y as f32);
        // Brightness as a fixed-point factor of 1/256ths.
        let gain = (brightness * 256.0).round().clamp(0.0, 65535.0) as u32;
        let scale = |p: [u8; 3]| p.map(|v| ((u32::from(v) * gain + 128) >> 8).min(255) as u8);
        let bands = out.par_chunks_mut(3 * BAND);
        let rays = self
            .points
            .par_chunks(BAND)
            .zip(self.levels.par_chunks(BAND));
        bands.zip(rays).for_each(|(band, (points, levels))| {
            let pixels = band.chunks_exact_mut(3);
            for ((pixel, &[rx, ry]), &level) in pixels.zip(points).zip(levels) {
                let colour = if level == SKY {
                    room
                } else {
                    // The robot-frame point moved rigidly into the world.
                    let wx = px + c * rx - s * ry;
                    let wy = py + s * rx + c * ry;
                    scale(texture.sample(level, wx, wy))
                };
                pixel.copy_from_slice(&colour);
            }
        });
    }
}
