//! The twin's rendered camera (feature `vision`): the grey frame a pinhole camera with the
//! configured intrinsics and mount (`[vision.render].mount`) sees of the arena's markers, which the ArUco detector
//! then reads like a real frame.
//!
//! Each marker's picture comes from OpenCV's `aruco::drawMarker` with a white quiet zone
//! of two cells, and is warped into the frame by the homography of its four corners,
//! far markers first. A marker is drawn when the line from the robot to it is clear of
//! walls, obstacles and blocks (the ideal sensor's test); lighting scales every grey level
//! and noise comes from the twin's seeded generator, so frames are deterministic.
//! Simplifications: no lens distortion, walls and floor are one flat grey.

use super::Marker;
use super::camera::clear_line;
use crate::clock::Clock;
use crate::data::MarkerSighting;
use crate::geometry::{Pose2, Segment};
use crate::perception::aruco::{Detector, VisionError};
use crate::perception::config::{MarkerSizes, RenderConfig, VisionConfig};
use crate::perception::frame::{CameraStatus, GrayFrame};
use nalgebra::Vector3;
use opencv::core::{BORDER_TRANSPARENT, Mat, Point2f, Rect, Scalar, Size};
use opencv::prelude::*;
use opencv::{aruco, imgproc};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use std::collections::HashMap;

/// Pixels per marker cell in the drawn marker pictures.
const CELL_PX: i32 = 12;
/// Cells across the black square of an ArUco original marker: 5 data bits and a border.
const MARKER_CELLS: f64 = 7.0;
/// White cells around the marker on its printed sheet (the quiet zone).
const QUIET_CELLS: i32 = 2;
/// Cells across the drawn picture: the marker plus the quiet zone on each side.
const SHEET_CELLS: f64 = MARKER_CELLS + 2.0 * QUIET_CELLS as f64;
/// Most fine pixels drawn for one marker when supersampling.
const FINE_PIXELS: f64 = 2.0e6;
/// Points closer than this in front of the camera are not drawn, metres.
const NEAR: f64 = 0.02;

/// Renders camera frames of markers for one camera.
#[derive(Debug)]
pub struct Renderer {
    sizes: MarkerSizes,
    light: RenderConfig,
    /// Marker pictures already drawn, by ID, lit.
    sheets: HashMap<u32, Mat>,
}

impl Clone for Renderer {
    fn clone(&self) -> Self {
        // The picture cache is rebuilt on demand.
        Self::new(&self.sizes, &self.light)
    }
}

/// A marker placed in the frame: its ID, distance and the sheet's four image corners.
struct Placed {
    id: u32,
    depth: f64,
    corners: [Point2f; 4],
}

impl Renderer {
    pub fn new(sizes: &MarkerSizes, light: &RenderConfig) -> Self {
        Self {
            sizes: sizes.clone(),
            light: light.clone(),
            sheets: HashMap::new(),
        }
    }

    /// The frame the camera of `detector` sees from `pose`, noise drawn from `rng`.
    pub fn render<'a>(
        &mut self,
        detector: &Detector,
        pose: Pose2,
        markers: impl IntoIterator<Item = &'a Marker>,
        occluders: &[&[Segment]],
        rng: &mut ChaCha8Rng,
    ) -> opencv::Result<GrayFrame> {
        let k = detector.intrinsics();
        let (w, h) = (k.width as i32, k.height as i32);
        let level = |g: f64| (g * self.light.brightness).clamp(0.0, 255.0);
        let mut frame = Mat::new_rows_cols_with_default(
            h,
            w,
            opencv::core::CV_8UC1,
            Scalar::all(level(self.light.background)),
        )?;
        let mut placed: Vec<Placed> = markers
            .into_iter()
            .filter_map(|m| self.place(detector, pose, m, occluders))
            .collect();
        // Painter's order: the farthest first, so nearer markers cover it.
        placed.sort_by(|a, b| b.depth.total_cmp(&a.depth));
        for p in &placed {
            self.paste(detector, p, &mut frame)?;
        }
        let mut out = GrayFrame {
            width: w as usize,
            height: h as usize,
            data: frame.data_bytes()?.to_vec(),
        };
        add_noise(&mut out.data, self.light.noise_std, rng);
        Ok(out)
    }

    /// Image corners of the sheet carrying `m`, if it faces the camera in front of it and
    /// the robot has a clear line to it.
    fn place(
        &self,
        detector: &Detector,
        pose: Pose2,
        m: &Marker,
        occluders: &[&[Segment]],
    ) -> Option<Placed> {
        let mount = detector.mount();
        let k = detector.intrinsics();
        let lens = mount.to_robot(Vector3::zeros());
        let eye = pose.transform_point(crate::geometry::Point2::new(lens.x, lens.y));
        let (ns, nc) = m.normal.sin_cos();
        // Facing the camera: the normal points back towards the eye.
        if nc * (eye.x - m.position.x) + ns * (eye.y - m.position.y) <= 0.0 {
            return None;
        }
        if !clear_line(pose.position(), m, occluders) {
            return None;
        }
        let half = self.sizes.side(m.id) * SHEET_CELLS / MARKER_CELLS / 2.0;
        let z = self.sizes.height(m.id);
        // Seen from the front the sheet's right is the normal turned clockwise.
        let right = (-ns, nc);
        let (s, c) = pose.theta.sin_cos();
        let mut corners = [Point2f::default(); 4];
        let mut depth = 0.0;
        // Top-left, top-right, bottom-right, bottom-left as seen from the front.
        for (i, (a, b)) in [(-1.0, 1.0), (1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)]
            .into_iter()
            .enumerate()
        {
            let wx = m.position.x + a * half * right.0;
            let wy = m.position.y + a * half * right.1;
            let wz = z + b * half;
            // World -> robot: rotate the offset by -theta (REP-103 planar pose).
            let (dx, dy) = (wx - pose.x, wy - pose.y);
            let robot = Vector3::new(c * dx + s * dy, -s * dx + c * dy, wz);
            let cam = mount.to_camera(robot);
            if cam.z < NEAR {
                return None;
            }
            let (u, v) = k.project(cam.x, cam.y, cam.z);
            corners[i] = Point2f::new(u as f32, v as f32);
            depth += cam.z / 4.0;
        }
        let (min_x, max_x) = span(corners.iter().map(|p| p.x));
        let (min_y, max_y) = span(corners.iter().map(|p| p.y));
        let overlaps =
            max_x >= 0.0 && max_y >= 0.0 && min_x < k.width as f32 && min_y < k.height as f32;
        overlaps.then_some(Placed {
            id: m.id,
            depth,
            corners,
        })
    }

    /// Warps the sheet of `p` into its bounding box in `frame`, supersampled: the box is
    /// drawn at `scale` times the resolution and area-averaged back down, so each pixel
    /// holds the mean of the scene over its area, as a camera's sensor does.
    fn paste(&mut self, detector: &Detector, p: &Placed, frame: &mut Mat) -> opencv::Result<()> {
        let (fw, fh) = (frame.cols(), frame.rows());
        let (min_x, max_x) = span(p.corners.iter().map(|c| c.x));
        let (min_y, max_y) = span(p.corners.iter().map(|c| c.y));
        let x0 = (min_x.floor() as i32).clamp(0, fw - 1);
        let y0 = (min_y.floor() as i32).clamp(0, fh - 1);
        let x1 = (max_x.ceil() as i32 + 1).clamp(x0 + 1, fw);
        let y1 = (max_y.ceil() as i32 + 1).clamp(y0 + 1, fh);
        let size = Size::new(x1 - x0, y1 - y0);
        let scale = supersampling(size);
        let fine = Size::new(size.width * scale, size.height * scale);
        let full = self.sheet(detector, p.id)?;
        // Shrink the picture to about its size in the fine image first (area averaging),
        // so the warp does not alias the cell edges of a far marker.
        let across = ((max_x - min_x).max(max_y - min_y).ceil() as i32 + 2) * scale;
        let mut small = Mat::default();
        let sheet = if across < full.cols() {
            imgproc::resize(
                full,
                &mut small,
                Size::new(across, across),
                0.0,
                0.0,
                imgproc::INTER_AREA,
            )?;
            &small
        } else {
            full
        };
        let n = sheet.cols() as f32;
        // The sheet's outer edges, in OpenCV's pixel-centre coordinates.
        let (lo, hi) = (-0.5, n - 0.5);
        let src = [
            Point2f::new(lo, lo),
            Point2f::new(hi, lo),
            Point2f::new(hi, hi),
            Point2f::new(lo, hi),
        ];
        // A frame pixel centre c is fine pixel centre scale (c + 0.5) - 0.5.
        let k = scale as f32;
        let dst = p.corners.map(|c| {
            Point2f::new(
                k * (c.x - x0 as f32 + 0.5) - 0.5,
                k * (c.y - y0 as f32 + 0.5) - 0.5,
            )
        });
        // The homography taking the sheet's corners to the image (Hartley & Zisserman 4.1).
        let homography = imgproc::get_perspective_transform_slice_def(&src, &dst)?;
        let mut roi = frame.roi_mut(Rect::new(x0, y0, size.width, size.height))?;
        // What is already drawn there, at the fine resolution (each pixel repeated, so
        // averaging it back down gives it back unchanged).
        let mut canvas = Mat::default();
        imgproc::resize(&roi, &mut canvas, fine, 0.0, 0.0, imgproc::INTER_NEAREST)?;
        imgproc::warp_perspective(
            sheet,
            &mut canvas,
            &homography,
            fine,
            imgproc::INTER_LINEAR,
            BORDER_TRANSPARENT,
            Scalar::default(),
        )?;
        let mut averaged = Mat::default();
        imgproc::resize(&canvas, &mut averaged, size, 0.0, 0.0, imgproc::INTER_AREA)?;
        averaged.copy_to(&mut roi)?;
        Ok(())
    }

    /// The lit picture of marker `id` with its white quiet zone, drawn once.
    fn sheet(&mut self, detector: &Detector, id: u32) -> opencv::Result<&Mat> {
        if !self.sheets.contains_key(&id) {
            let inner = (MARKER_CELLS as i32) * CELL_PX;
            let mut marker = Mat::default();
            aruco::draw_marker(detector.dictionary(), id as i32, inner, &mut marker, 1)?;
            let mut sheet = Mat::default();
            opencv::core::copy_make_border(
                &marker,
                &mut sheet,
                QUIET_CELLS * CELL_PX,
                QUIET_CELLS * CELL_PX,
                QUIET_CELLS * CELL_PX,
                QUIET_CELLS * CELL_PX,
                opencv::core::BORDER_CONSTANT,
                Scalar::all(255.0),
            )?;
            // Lighting: black cells -> black * brightness, white -> white * brightness.
            let b = self.light.brightness;
            let (lo, hi) = (self.light.black * b, self.light.white * b);
            let mut lit = Mat::default();
            sheet.convert_to(&mut lit, opencv::core::CV_8U, (hi - lo) / 255.0, lo)?;
            self.sheets.insert(id, lit);
        }
        Ok(&self.sheets[&id])
    }
}

/// Fine pixels per frame pixel along each axis for a box of `size`: 4, or fewer for a box
/// so large that 4 would draw over `FINE_PIXELS`.
fn supersampling(size: Size) -> i32 {
    let area = f64::from(size.width) * f64::from(size.height);
    ((FINE_PIXELS / area).sqrt().floor() as i32).clamp(1, 4)
}

fn span(values: impl Iterator<Item = f32>) -> (f32, f32) {
    values.fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    })
}

/// Adds zero-mean noise of standard deviation `std` to every pixel: the sum of two uniform
/// bytes is triangular with variance 2 * 256^2 / 12 (sum of independent uniforms).
fn add_noise(pixels: &mut [u8], std: f64, rng: &mut ChaCha8Rng) {
    if std <= 0.0 {
        return;
    }
    let scale = std / (2.0f64 * 256.0 * 256.0 / 12.0).sqrt();
    let table: Vec<i16> = (0..511)
        .map(|s| ((f64::from(s) - 255.0) * scale).round() as i16)
        .collect();
    for chunk in pixels.chunks_mut(4) {
        let bits: u64 = rng.random();
        for (k, p) in chunk.iter_mut().enumerate() {
            let a = (bits >> (16 * k)) as u8 as usize;
            let b = (bits >> (16 * k + 8)) as u8 as usize;
            *p = (i16::from(*p) + table[a + b]).clamp(0, 255) as u8;
        }
    }
}

/// The twin's camera with the ArUco detector behind it: frames in, sightings out.
#[derive(Clone)]
pub struct RenderedCamera {
    renderer: Renderer,
    detector: Detector,
    stopwatch: Option<std::sync::Arc<dyn Clock>>,
}

impl std::fmt::Debug for RenderedCamera {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RenderedCamera")
            .field("detector", &self.detector)
            .finish_non_exhaustive()
    }
}

impl RenderedCamera {
    /// The camera of `vision.render.mount` (not the real robot's `vision.mount`), whose
    /// sightings end at `max_range` metres or the detector's own limit if nearer.
    pub fn new(
        vision: &VisionConfig,
        max_range: f64,
        stopwatch: Option<std::sync::Arc<dyn Clock>>,
    ) -> Result<Self, VisionError> {
        let mut twin = vision.clone();
        twin.mount = vision.render.mount.clone();
        twin.detector.max_range = twin.detector.max_range.min(max_range);
        Ok(Self {
            renderer: Renderer::new(&vision.markers, &vision.render),
            detector: Detector::from_config(&twin)?,
            stopwatch,
        })
    }

    /// The detector reading this camera's frames, with its mount and intrinsics.
    pub fn detector(&self) -> &Detector {
        &self.detector
    }

    /// Renders the frame seen from `pose`, detects its markers and reports both.
    pub fn capture<'a>(
        &mut self,
        pose: Pose2,
        markers: impl IntoIterator<Item = &'a Marker>,
        occluders: &[&[Segment]],
        rng: &mut ChaCha8Rng,
    ) -> (Vec<MarkerSighting>, CameraStatus) {
        let frame = match self
            .renderer
            .render(&self.detector, pose, markers, occluders, rng)
        {
            Ok(f) => f,
            Err(e) => return (Vec::new(), CameraStatus::failed(e.to_string())),
        };
        self.detector.read(&frame, self.stopwatch.as_deref())
    }
}
