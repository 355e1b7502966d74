//! The lane camera's pipeline: one colour frame through the lane masks, the bird's-eye
//! windows and fits, the lamp and arm finders, and their filters, into a `LaneSighting`.

use super::barrier::{ArmFinder, BarrierObservation};
use super::barrier_filter::BarrierFilter;
use super::birdseye::BirdsEye;
use super::config::{LaneVisionConfig, LaneVisionError};
use super::lane_fit::{FitLimits, LineTrack, curvature};
use super::light::LightFinder;
use super::masks::MaskMaker;
use super::value_loop::ValueLoop;
use super::windows::{GridMask, LineFound, WindowSearch, find_line, x_at};
use crate::clock::Clock;
use crate::data::{BarrierSeen, LaneSighting, LightSeen};
use crate::perception::colour::BgrFrame;
use crate::perception::lane_camera::LaneCameraConfig;
use crate::sim::track::{ARM_HEIGHT, ARM_THICKNESS, LAMP_RADIUS, lamp_height};
use opencv::core::Mat;
use opencv::imgproc;
use opencv::prelude::*;

/// Thumbnail size handed to the console's lane panel, pixels.
pub const THUMBNAIL: (usize, usize) = (48, 24);

/// What one frame shows of the light and the barrier, before any filtering.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ObjectDetections {
    pub light: Option<LightSeen>,
    pub barrier: Option<BarrierObservation>,
}

/// The lane camera's pipeline and its frame-to-frame state.
pub struct LanePipeline {
    cfg: LaneVisionConfig,
    eye: BirdsEye,
    masks: MaskMaker,
    lights: LightFinder,
    arm: ArmFinder,
    value: ValueLoop,
    yellow: LineTrack,
    white: LineTrack,
    barrier: BarrierFilter,
    /// The arm as last seen, while the filter tracks it.
    last_arm: Option<BarrierObservation>,
    limits: FitLimits,
    hsv: Mat,
}

impl LanePipeline {
    pub fn new(cfg: &LaneVisionConfig, camera: &LaneCameraConfig) -> Result<Self, LaneVisionError> {
        if let Some((field, value, reason)) = cfg.invalid() {
            return Err(LaneVisionError::Field {
                field,
                value,
                reason,
            });
        }
        if let Some((field, value, reason)) = camera.invalid() {
            return Err(LaneVisionError::Camera {
                field,
                value,
                reason,
            });
        }
        let eye = BirdsEye::new(&cfg.view, camera).map_err(LaneVisionError::View)?;
        let horizon = eye.horizon_row() as i32 + cfg.horizon_margin_px as i32;
        let frames = cfg.filter_frames as usize;
        Ok(Self {
            masks: MaskMaker::new(cfg, &eye)?,
            lights: LightFinder {
                bottom: horizon,
                eye: eye.clone(),
                lamp_radius: LAMP_RADIUS,
                lamp_height,
            },
            arm: ArmFinder {
                eye: eye.clone(),
                arm_height: ARM_HEIGHT,
                arm_thickness: ARM_THICKNESS,
            },
            value: ValueLoop::new(
                cfg.value_floor,
                cfg.value_floor_bounds,
                cfg.pixel_ratio_band,
                cfg.pi_gains,
            ),
            yellow: LineTrack::new(frames),
            white: LineTrack::new(frames),
            barrier: BarrierFilter::new(cfg.barrier_forget_frames as usize),
            last_arm: None,
            limits: FitLimits {
                max_curvature: cfg.max_curvature,
                max_jump_mm: cfg.max_jump * 1000.0,
                rows_mm: eye.rows() as f64 * eye.cell_mm(),
            },
            cfg: cfg.clone(),
            eye,
            hsv: Mat::default(),
        })
    }

    /// The brightness floor the lane masks use next.
    pub fn value_floor(&self) -> f64 {
        self.value.floor()
    }

    /// A whole frame through every stage, with the temporal filters updated.
    pub fn read(&mut self, frame: &BgrFrame, stopwatch: Option<&dyn Clock>) -> LaneSighting {
        let started = stopwatch.map(|s| s.now());
        let mut sighting = self.try_read(frame).unwrap_or_else(LaneSighting::failed);
        if sighting.thumbnail.is_none() && frame.data.len() == 3 * frame.width * frame.height {
            sighting.thumbnail = Some(frame.thumbnail(THUMBNAIL.0, THUMBNAIL.1));
        }
        sighting.latency = stopwatch.zip(started).map(|(s, t0)| s.now() - t0);
        sighting
    }

    /// The light and the barrier as this frame alone shows them (no filter is updated).
    pub fn detect_objects(&mut self, frame: &BgrFrame) -> ObjectDetections {
        self.load_hsv(frame)
            .and_then(|()| self.objects())
            .unwrap_or_default()
    }

    /// Forgets every frame seen: lines, barrier and the brightness loop.
    pub fn reset(&mut self) {
        self.value.reset();
        self.yellow.reset();
        self.white.reset();
        self.barrier.reset();
        self.last_arm = None;
    }

    fn load_hsv(&mut self, frame: &BgrFrame) -> Result<(), String> {
        let k = self.eye.intrinsics();
        if (frame.width, frame.height) != (k.width as usize, k.height as usize)
            || frame.data.len() != 3 * frame.width * frame.height
        {
            return Err(format!(
                "frame is {}x{} ({} bytes) but the lane camera is {}x{}",
                frame.width,
                frame.height,
                frame.data.len(),
                k.width,
                k.height
            ));
        }
        // The frame's own bytes seen as a matrix, not copied.
        let (rows, cols) = (frame.height as i32, frame.width as i32);
        let bgr = Mat::new_rows_cols_with_bytes::<opencv::core::Vec3b>(rows, cols, &frame.data)
            .map_err(|e| e.to_string())?;
        imgproc::cvt_color_def(&bgr, &mut self.hsv, imgproc::COLOR_BGR2HSV)
            .map_err(|e| e.to_string())
    }

    fn objects(&self) -> Result<ObjectDetections, String> {
        objects_in(&self.lights, &self.arm, &self.hsv)
    }

    fn try_read(&mut self, frame: &BgrFrame) -> Result<LaneSighting, String> {
        self.load_hsv(frame)?;
        // The lane's masks (and the console's thumbnail) and the light and barrier are
        // found from the same HSV frame at once, on two cores where there are two.
        let ((masks, thumbnail), objects) = rayon::join(
            || {
                let masks = self.masks.masks(&self.hsv, self.value.floor());
                (masks, frame.thumbnail(THUMBNAIL.0, THUMBNAIL.1))
            },
            || objects_in(&self.lights, &self.arm, &self.hsv),
        );
        let masks = masks.map_err(|e| e.to_string())?;
        let cells = self.eye.cols() * self.eye.rows();
        let pixel_ratio = masks.lane_cells as f64 / cells as f64;
        let yellow_found = self.line(&masks.yellow)?;
        let white_found = self.line(&masks.white)?;
        (self.value).update(pixel_ratio, yellow_found.is_some() || white_found.is_some());
        let yellow = self.yellow.offer(yellow_found, &self.limits);
        let white = self.white.offer(white_found, &self.limits);
        let (error_px, curvature) = self.centre(yellow, white).unzip();
        let objects = objects?;
        let observed = objects.barrier.map(|b| (b.state, b.confidence));
        let belief = self.barrier.step(observed);
        self.last_arm = belief.and(objects.barrier.or(self.last_arm));
        // The state is the filter's; the angle and range are the arm's as last seen.
        let barrier = belief.zip(self.last_arm).map(|(belief, arm)| BarrierSeen {
            state: self.barrier.state(),
            angle_deg: arm.angle_deg,
            range: arm.range,
            belief,
            fresh: objects.barrier.is_some(),
        });
        Ok(LaneSighting {
            error_px,
            curvature,
            yellow,
            white,
            pixel_ratio,
            light: objects.light,
            barrier,
            latency: None,
            thumbnail: Some(thumbnail),
            error: None,
        })
    }

    fn line(&self, grid: &Mat) -> Result<Option<LineFound>, String> {
        let data = grid.data_bytes().map_err(|e| e.to_string())?;
        let mask = GridMask {
            cols: self.eye.cols(),
            rows: self.eye.rows(),
            data,
        };
        Ok(find_line(
            &mask,
            &WindowSearch {
                windows: self.cfg.windows as usize,
                base_width_mm: self.cfg.window_width_mm,
                cell_mm: self.eye.cell_mm(),
            },
        ))
    }

    /// The lane centre's offset from the robot's axis at the look-ahead row, millimetres
    /// (positive right), and the lane's curvature there: the mean of the two lines, or one
    /// line moved half a lane width towards the other.
    fn centre(&self, yellow: Option<[f64; 3]>, white: Option<[f64; 3]>) -> Option<(f64, f64)> {
        let y = self.eye.row_mm_of_ahead(self.cfg.look_ahead);
        let half = self.cfg.lane_width * 1000.0 / 2.0;
        let axis = self.eye.width_mm() / 2.0;
        // Two lines closer than half a lane, or farther than a lane and a half, are not
        // this lane's: the white mask is the one walls, arms and glare fool, so the yellow
        // line alone is taken.
        let apart = |l: &[f64; 3], r: &[f64; 3]| x_at(r, y) - x_at(l, y);
        let white = white.filter(|r| {
            yellow.is_none_or(|l| (0.5 * 2.0 * half..=1.5 * 2.0 * half).contains(&apart(&l, r)))
        });
        let (x, fit) = match (yellow, white) {
            (Some(l), Some(r)) => (
                (x_at(&l, y) + x_at(&r, y)) / 2.0,
                [0, 1, 2].map(|i| (l[i] + r[i]) / 2.0),
            ),
            // Yellow is the left line: the centre is half a lane to its right (+x).
            (Some(l), None) => (x_at(&l, y) + half, l),
            (None, Some(r)) => (x_at(&r, y) - half, r),
            (None, None) => return None,
        };
        // LaneSighting::MM_PER_PX = 1: the error in millimetres is the error in pixels.
        Some((
            (x - axis) / crate::data::LaneSighting::MM_PER_PX,
            curvature(&fit, y),
        ))
    }
}

/// The light and the barrier in `hsv` (a whole frame in HSV).
fn objects_in(
    lights: &LightFinder,
    arm: &ArmFinder,
    hsv: &Mat,
) -> Result<ObjectDetections, String> {
    Ok(ObjectDetections {
        light: lights.find(hsv).map_err(|e| e.to_string())?,
        barrier: arm.find(hsv).map_err(|e| e.to_string())?,
    })
}
