//! Draws what the twin's camera sees of the arena's markers: the grey frame a pinhole
//! camera with the configured intrinsics and mount (`[vision.render].mount`) sees.
//!
//! Each marker's picture comes from OpenCV's `aruco::drawMarker` with a white quiet zone
//! of two cells, and is painted into the frame through the homography of its four corners
//! (`sheet_paint`), far markers first. A marker is drawn when the line from the robot to it
//! is clear of walls, obstacles and blocks (the ideal sensor's test); lighting scales every
//! grey level and noise comes from the twin's seeded generator, so frames are
//! deterministic. Simplifications: no lens distortion, walls and floor are one flat grey.
//!
//! A frame is drawn whole, or only in the regions round the markers whose sightings the
//! detector could accept (`readable`), with the same pixels there.

use super::Marker;
use super::camera::clear_line;
use super::frame_noise::{add_noise, add_noise_in};
use super::readable::{self, Footprint, Limits};
use super::sheet_paint::{self, Homography, Sheet};
use crate::geometry::{Pose2, Segment};
use crate::perception::aruco::Detector;
use crate::perception::config::{MarkerSizes, RenderConfig};
use crate::perception::frame::GrayFrame;
use crate::perception::region::Region;
use nalgebra::Vector3;
use opencv::core::{Mat, Point2f, Scalar};
use opencv::prelude::*;
use opencv::{aruco, imgproc};
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
/// Pixels across a full-size sheet picture.
const SHEET_PX: usize = (SHEET_CELLS as usize) * CELL_PX as usize;
/// Most samples taken for one marker when supersampling.
const FINE_PIXELS: f64 = 2.0e6;
/// Points closer than this in front of the camera are not drawn, metres.
const NEAR: f64 = 0.02;
/// Shrunk sheet pictures kept for far markers before the cache starts again.
const SHRUNK_KEPT: usize = 512;

/// Renders camera frames of markers for one camera.
#[derive(Debug)]
pub struct Renderer {
    sizes: MarkerSizes,
    light: RenderConfig,
    /// Marker pictures already drawn and lit, by ID and size across.
    sheets: HashMap<(u32, usize), Sheet>,
}

impl Clone for Renderer {
    fn clone(&self) -> Self {
        // The picture cache is rebuilt on demand.
        Self::new(&self.sizes, &self.light)
    }
}

/// A marker placed in the frame: its ID, distance, the sheet's four image corners, and
/// where the detector would look for it.
struct Placed {
    id: u32,
    depth: f64,
    corners: [Point2f; 4],
    /// Image corners of the black square.
    square: [[f64; 2]; 4],
    /// Planar range from the robot centre, metres.
    range: f64,
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
        let (w, h) = (k.width as usize, k.height as usize);
        let mut frame = GrayFrame::filled(w, h, self.background());
        let whole = [Region::whole(w, h)];
        for p in &self.scene(detector, pose, markers, occluders) {
            self.paste(detector, p, &mut frame, &whole)?;
        }
        add_noise(&mut frame.data, self.light.noise_std, rng);
        Ok(frame)
    }

    /// Draws into `frame` (of the camera's size) what `render` would draw, but only in the
    /// regions round the markers whose sightings the detector could accept (`readable`),
    /// and returns the windows to search for their squares; pixels outside the regions
    /// are left unspecified. `rng` moves on as `render` moves it.
    pub fn render_readable<'a>(
        &mut self,
        detector: &Detector,
        pose: Pose2,
        markers: impl IntoIterator<Item = &'a Marker>,
        occluders: &[&[Segment]],
        rng: &mut ChaCha8Rng,
        frame: &mut GrayFrame,
    ) -> opencv::Result<Vec<Region>> {
        let (w, h) = (frame.width, frame.height);
        let placed = self.scene(detector, pose, markers, occluders);
        let footprints: Vec<Footprint> = placed
            .iter()
            .map(|p| Footprint {
                sheet: sheet_box(&p.corners, w, h),
                square: p.square,
                range: p.range,
            })
            .collect();
        let plan = readable::plan(&footprints, w, h, &limits(detector));
        let background = self.background();
        for r in &plan.regions {
            for y in r.y0..r.y1 {
                frame.data[y * w + r.x0..y * w + r.x1].fill(background);
            }
        }
        for (p, _) in placed.iter().zip(&plan.draw).filter(|(_, draw)| **draw) {
            self.paste(detector, p, frame, &plan.regions)?;
        }
        add_noise_in(&mut frame.data, w, &plan.regions, self.light.noise_std, rng);
        Ok(plan.windows)
    }

    /// The lit grey of walls and floor (rounded half to even, as OpenCV rounds).
    fn background(&self) -> u8 {
        (self.light.background * self.light.brightness)
            .clamp(0.0, 255.0)
            .round_ties_even() as u8
    }

    /// The markers facing the camera, in sight and in frame, farthest first (painter's
    /// order: nearer markers cover farther ones).
    fn scene<'a>(
        &self,
        detector: &Detector,
        pose: Pose2,
        markers: impl IntoIterator<Item = &'a Marker>,
        occluders: &[&[Segment]],
    ) -> Vec<Placed> {
        let mut placed: Vec<Placed> = markers
            .into_iter()
            .filter_map(|m| self.place(detector, pose, m, occluders))
            .collect();
        placed.sort_by(|a, b| b.depth.total_cmp(&a.depth));
        placed
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
        let side = self.sizes.side(m.id);
        let z = self.sizes.height(m.id);
        // Seen from the front the sheet's right is the normal turned clockwise.
        let right = (-ns, nc);
        let (s, c) = pose.theta.sin_cos();
        // Image corners of the square of side 2 half centred on the marker, and their
        // mean distance ahead of the camera; none when a corner is not in front of it.
        let project = |half: f64| {
            let mut corners = [[0.0; 2]; 4];
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
                corners[i] = [u, v];
                depth += cam.z / 4.0;
            }
            Some((corners, depth))
        };
        let (sheet, depth) = project(side * SHEET_CELLS / MARKER_CELLS / 2.0)?;
        let corners = sheet.map(|[u, v]| Point2f::new(u as f32, v as f32));
        let (min_x, max_x) = span(corners.iter().map(|p| p.x));
        let (min_y, max_y) = span(corners.iter().map(|p| p.y));
        let overlaps =
            max_x >= 0.0 && max_y >= 0.0 && min_x < k.width as f32 && min_y < k.height as f32;
        if !overlaps {
            return None;
        }
        // Inside the sheet, so in front of the camera too.
        let (square, _) = project(side / 2.0)?;
        Some(Placed {
            id: m.id,
            depth,
            corners,
            square,
            range: (m.position.x - pose.x).hypot(m.position.y - pose.y),
        })
    }

    /// Paints the sheet of `p` into the part of its bounding box in `frame` inside `clip`,
    /// each pixel the mean of `supersampling` x `supersampling` samples over its area, as a
    /// camera's sensor averages the scene over each pixel. A pixel's grey depends on
    /// nothing but its own samples, so clipping leaves the pixels painted unchanged.
    fn paste(
        &mut self,
        detector: &Detector,
        p: &Placed,
        frame: &mut GrayFrame,
        clip: &[Region],
    ) -> opencv::Result<()> {
        let bounds = sheet_box(&p.corners, frame.width, frame.height);
        let scale = supersampling(&bounds);
        // Far markers are painted from a picture shrunk (area averaging) to about their
        // size in samples, so the samples do not alias its cell edges.
        let (min_x, max_x) = span(p.corners.iter().map(|c| c.x));
        let (min_y, max_y) = span(p.corners.iter().map(|c| c.y));
        let across = ((max_x - min_x).max(max_y - min_y).ceil() as usize + 2) * scale;
        let sheet = self.sheet(detector, p.id, across.min(SHEET_PX))?;
        let n = sheet.side() as f32;
        // The sheet's outer edges, in pixel-centre coordinates.
        let (lo, hi) = (-0.5, n - 0.5);
        let edges = [
            Point2f::new(lo, lo),
            Point2f::new(hi, lo),
            Point2f::new(hi, hi),
            Point2f::new(lo, hi),
        ];
        // The homography taking the sheet's corners in the image back onto the sheet
        // (Hartley & Zisserman 4.1).
        let m = imgproc::get_perspective_transform_slice_def(&p.corners, &edges)?;
        let mut to_sheet: Homography = [0.0; 9];
        for (k, h) in to_sheet.iter_mut().enumerate() {
            *h = *m.at_2d::<f64>(k as i32 / 3, k as i32 % 3)?;
        }
        let to_sheet = sheet_paint::facing(to_sheet, p.corners[0].x.into(), p.corners[0].y.into());
        for part in clip.iter().filter_map(|r| r.intersection(&bounds)) {
            sheet_paint::paint(&mut frame.data, frame.width, part, sheet, &to_sheet, scale);
        }
        Ok(())
    }

    /// The lit picture of marker `id` with its white quiet zone, `across` pixels wide:
    /// drawn once at full size, and shrunk from that by area averaging.
    fn sheet(&mut self, detector: &Detector, id: u32, across: usize) -> opencv::Result<&Sheet> {
        if !self.sheets.contains_key(&(id, SHEET_PX)) {
            let full = self.draw_sheet(detector, id)?;
            self.sheets.insert((id, SHEET_PX), full);
        }
        if !self.sheets.contains_key(&(id, across)) {
            if self.sheets.len() > SHRUNK_KEPT {
                self.sheets.retain(|&(_, side), _| side == SHEET_PX);
            }
            let full = &self.sheets[&(id, SHEET_PX)];
            let side = SHEET_PX as i32;
            let picture = Mat::new_rows_cols_with_data(side, side, full.pixels())?;
            let mut small = Mat::default();
            let size = opencv::core::Size::new(across as i32, across as i32);
            imgproc::resize(&picture, &mut small, size, 0.0, 0.0, imgproc::INTER_AREA)?;
            let shrunk = Sheet::new(across, small.data_bytes()?.to_vec());
            self.sheets.insert((id, across), shrunk);
        }
        Ok(&self.sheets[&(id, across)])
    }

    /// Marker `id` drawn by OpenCV, framed in white and lit.
    fn draw_sheet(&self, detector: &Detector, id: u32) -> opencv::Result<Sheet> {
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
        Ok(Sheet::new(SHEET_PX, lit.data_bytes()?.to_vec()))
    }
}

/// Samples per frame pixel along each axis for a box of `bounds`: 4, or fewer for a box
/// so large that 4 would take over `FINE_PIXELS` samples.
fn supersampling(bounds: &Region) -> usize {
    let area = (bounds.width() * bounds.height()) as f64;
    ((FINE_PIXELS / area).sqrt().floor() as usize).clamp(1, 4)
}

fn span(values: impl Iterator<Item = f32>) -> (f32, f32) {
    values.fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    })
}

/// The pixels a paste of the sheet with image `corners` writes in a `width` x `height`
/// frame: its bounding box, a pixel wider and taller, kept in the frame.
fn sheet_box(corners: &[Point2f; 4], width: usize, height: usize) -> Region {
    let (fw, fh) = (width as i32, height as i32);
    let (min_x, max_x) = span(corners.iter().map(|c| c.x));
    let (min_y, max_y) = span(corners.iter().map(|c| c.y));
    let x0 = (min_x.floor() as i32).clamp(0, fw - 1);
    let y0 = (min_y.floor() as i32).clamp(0, fh - 1);
    let x1 = (max_x.ceil() as i32 + 1).clamp(x0 + 1, fw);
    let y1 = (max_y.ceil() as i32 + 1).clamp(y0 + 1, fh);
    Region {
        x0: x0 as usize,
        y0: y0 as usize,
        x1: x1 as usize,
        y1: y1 as usize,
    }
}

/// What the detector of `detector` refuses, for `readable`.
fn limits(detector: &Detector) -> Limits {
    let d = &detector.config().detector;
    Limits {
        max_range: d.max_range,
        min_side_px: d.min_side_px,
        threshold_window: d.adaptive_thresh_win_size_max.max(0) as usize,
    }
}
