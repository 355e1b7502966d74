//! The floor pass: where each pixel's ray meets the floor, worked out once in the robot's
//! frame (the camera's mount is fixed) and cut into stretches of rows that sample the
//! texture alike and meet the floor at even steps; per frame each stretch is moved
//! rigidly into the world and walked along the floor texture (`scanline`).

use super::scanline::{FloorLine, RigidMove};
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
/// Pixels painted as one piece of work when the frame is shared among the cores, about.
const BAND: usize = 640 * 16;
/// A stretch of a row ends where a pixel's floor point strays this far from even steps
/// from its start, metres (a hundredth of the finest cell).
pub const EVEN: f64 = 5e-5;

/// A stretch of one image row: its first pixel, how it samples the texture (`SKY` for
/// none) and where it meets the floor in the robot frame.
#[derive(Clone, Copy, Debug)]
struct Run {
    start: usize,
    code: u8,
    line: FloorLine,
}

/// For every pixel, where its ray meets the floor in the robot frame and how to sample
/// the texture there (`FloorTexture::sample`'s code) for the floor it spans.
#[derive(Clone)]
pub struct FloorRays {
    width: usize,
    points: Vec<[f32; 2]>,
    levels: Vec<u8>,
    /// Each row's stretches, in order: a stretch ends where the next begins or the row
    /// does.
    runs: Vec<Vec<Run>>,
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
        let mut runs = Vec::with_capacity(h);
        for y in 0..h {
            let mut row: Vec<Run> = Vec::new();
            for x in 0..w {
                let (u, v) = (x as f64, y as f64);
                let point = floor_point(k, mount, u, v);
                let code = point.map_or(SKY, |p| {
                    // The floor one pixel over, across and down: the pixel's footprint.
                    let span = |q: Option<[f64; 2]>| {
                        q.map_or(f64::INFINITY, |q| (q[0] - p[0]).hypot(q[1] - p[1]))
                    };
                    let over = span(floor_point(k, mount, u + 1.0, v));
                    let footprint = over.max(span(floor_point(k, mount, u, v + 1.0)));
                    // The level whose cell is nearest the footprint (mipmap selection,
                    // Williams 1983: level = log2(footprint / cell)), sampled bilinearly
                    // where a cell spans two pixels or more.
                    let ratio = footprint / cell;
                    let level = ratio.log2().round().clamp(0.0, (LEVELS - 1) as f64) as u8;
                    if ratio < MAGNIFIED { 0 } else { level + 1 }
                });
                let p = point.unwrap_or([0.0; 2]);
                points.push(p.map(|c| c as f32));
                levels.push(code);
                extend(&mut row, x, code, p);
            }
            runs.push(row);
        }
        Self {
            width: w,
            points,
            levels,
            runs,
        }
    }

    /// Where pixel `i`'s ray meets the floor, in the robot frame; None above the horizon.
    #[inline]
    pub fn point(&self, i: usize) -> Option<[f32; 2]> {
        (self.levels[i] != SKY).then(|| self.points[i])
    }

    /// Row `y`'s stretches that see the floor: first pixel, end (exclusive) and where they
    /// meet the floor in the robot frame (every pixel within `EVEN` of the line's steps).
    pub fn floor_stretches(&self, y: usize) -> impl Iterator<Item = (usize, usize, FloorLine)> {
        let runs = &self.runs[y];
        let width = self.width;
        (runs.iter().enumerate())
            .filter(|(_, run)| run.code != SKY)
            .map(move |(k, run)| {
                let end = runs.get(k + 1).map_or(width, |r| r.start);
                (run.start, end, run.line)
            })
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
        let pose = RigidMove::of(pose);
        let tone = tone(brightness);
        let width = self.width.max(1);
        let rows = (BAND / width).max(1);
        let bands = out.par_chunks_mut(3 * rows * width);
        let runs = self.runs.par_chunks(rows);
        bands.zip(runs).for_each(|(band, runs)| {
            for (row, runs) in band.chunks_mut(3 * width).zip(runs) {
                for (k, run) in runs.iter().enumerate() {
                    let end = runs.get(k + 1).map_or(width, |r| r.start);
                    let out = &mut row[3 * run.start..3 * end];
                    if run.code == SKY {
                        for pixel in out.chunks_exact_mut(3) {
                            pixel.copy_from_slice(&room);
                        }
                        continue;
                    }
                    let line = FloorLine {
                        start: pose.apply(run.line.start),
                        step: pose.rotate(run.line.step),
                    };
                    texture.paint_line(run.code, &line, &tone, out);
                }
            }
        });
    }
}

/// Adds pixel `x` (sampled by `code`, meeting the floor at `p`) to the row's stretches:
/// to the last one if it samples alike and `p` lies on its even steps, else as a new one.
fn extend(row: &mut Vec<Run>, x: usize, code: u8, p: [f64; 2]) {
    if let Some(run) = row.last_mut()
        && run.code == code
    {
        let n = (x - run.start) as f64;
        if n == 1.0 {
            run.line.step = [p[0] - run.line.start[0], p[1] - run.line.start[1]];
            return;
        }
        let even = [0, 1].map(|i| run.line.start[i] + n * run.line.step[i]);
        if code == SKY || (even[0] - p[0]).hypot(even[1] - p[1]) <= EVEN {
            return;
        }
    }
    row.push(Run {
        start: x,
        code,
        line: FloorLine {
            start: p,
            step: [0.0; 2],
        },
    });
}

/// Brightness as a table from each byte to its scaled value, in fixed point of 1/256ths.
fn tone(brightness: f64) -> [u8; 256] {
    let gain = (brightness * 256.0).round().clamp(0.0, 65535.0) as u32;
    std::array::from_fn(|v| ((v as u32 * gain + 128) >> 8).min(255) as u8)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Point2;
    use crate::perception::lane_camera::LaneCameraConfig;
    use crate::sim::track::Track;

    /// Every pixel moved and sampled on its own through `FloorTexture::sample`.
    fn paint_pixel_by_pixel(
        rays: &FloorRays,
        texture: &FloorTexture,
        pose: Pose2,
        brightness: f64,
        room: [u8; 3],
    ) -> Vec<u8> {
        let (pose, tone) = (RigidMove::of(pose), tone(brightness));
        let mut out = Vec::new();
        for (&p, &level) in rays.points.iter().zip(&rays.levels) {
            let colour = if level == SKY {
                room
            } else {
                let [x, y] = pose.apply(p.map(f64::from));
                let colour = texture.sample(level, x as f32, y as f32);
                colour.map(|v| tone[usize::from(v)])
            };
            out.extend(colour);
        }
        out
    }

    /// A camera of the default mount turned `roll` degrees about its optical axis.
    fn camera(roll: f64) -> LaneCameraConfig {
        let mut camera = LaneCameraConfig::default();
        camera.mount.rotation_deg[1] = roll;
        camera
    }

    #[test]
    fn walking_rows_gives_the_colours_of_sampling_each_pixel_on_its_own() {
        let points = [(-2.0, -1.5), (2.0, -1.5), (2.0, 1.5), (-2.0, 1.5)];
        let corners = points.map(|(x, y)| Point2::new(x, y));
        let track = Track::new(&corners, 0.4, 0.025, true, 0.1).unwrap();
        let shadow = vec![
            Point2::new(-1.0, -2.0),
            Point2::new(0.5, -2.0),
            Point2::new(0.0, 0.0),
        ];
        let texture = FloorTexture::new(
            Point2::new(-3.0, -2.5),
            Point2::new(3.0, 2.5),
            &track,
            &[shadow],
        );
        let room = [40, 50, 60];
        // On the lane, across it, at the floor's edge looking out, and turned every way;
        // a level camera and one rolled, whose rows meet the floor unevenly.
        let poses = [
            Pose2::new(-1.0, -1.5, 0.0),
            Pose2::new(1.9, -1.2, 1.3),
            Pose2::new(2.8, 2.3, 0.7),
            Pose2::new(0.0, 0.0, -2.6),
        ];
        for roll in [0.0, 8.0] {
            let camera = camera(roll);
            let rays = FloorRays::new(&camera.intrinsics(), &camera.mount(), texture.cell());
            let stretches: usize = rays.runs.iter().map(Vec::len).sum();
            let rows = rays.runs.len();
            if roll == 0.0 {
                assert!(stretches < 3 * rows, "{stretches} stretches in {rows} rows");
            } else {
                assert!(stretches > 4 * rows, "{stretches} stretches in {rows} rows");
            }
            for pose in poses {
                for brightness in [0.55, 1.0, 1.35] {
                    let mut out = vec![0u8; 3 * rays.levels.len()];
                    rays.paint(&texture, pose, brightness, room, &mut out);
                    let want = paint_pixel_by_pixel(&rays, &texture, pose, brightness, room);
                    // Fixed point rounds a texel's edge now and then the other way.
                    let off = (out.chunks(3).zip(want.chunks(3)))
                        .filter(|(a, b)| a.iter().zip(*b).any(|(p, q)| p.abs_diff(*q) > 2))
                        .count();
                    assert!(
                        off * 500 < rays.levels.len(),
                        "roll {roll}, {pose:?} at {brightness}: {off} pixels differ"
                    );
                }
            }
        }
    }
}
