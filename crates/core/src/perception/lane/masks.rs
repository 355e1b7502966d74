//! The lane masks (seed 000 §2.1.2-§2.1.3): the floor rows warped onto the bird's-eye
//! grid, yellow and white paint picked out there in HSV above the PI loop's brightness
//! floor, glare taken out of both, and only what stands out from the floor around it.
//!
//! The last test is navdeck's: paint is a narrow stripe brighter than the floor beside it,
//! so the masks keep only cells brighter than the grid's morphological opening (a white
//! top-hat, Soille 2003 §4.5) by `paint_above_floor`. On the bird's-eye grid tape has one
//! width near and far, so one opening wider than the tape serves the whole view; a wall
//! seen above the floor, lit floor between hard shadows and a floor brightened by the
//! lighting are wider than that, and drop out whatever their brightness.

use super::birdseye::BirdsEye;
use super::config::LaneVisionConfig;
use opencv::core::{self, Mat, Rect, Scalar, Size, Vector};
use opencv::imgproc;
use opencv::prelude::*;

/// The lane masks of one frame on the bird's-eye grid, and how many cells passed.
pub struct LaneMasks {
    pub yellow: Mat,
    pub white: Mat,
    /// Yellow and white cells of the grid, after glare was taken out.
    pub lane_cells: usize,
}

/// Makes lane masks for one camera: the warp and kernels built once, buffers reused.
pub struct MaskMaker {
    hue: [f64; 2],
    yellow_saturation_floor: f64,
    white_saturation_ceiling: f64,
    glare_value: f64,
    paint_above_floor: f64,
    /// Rows from here down can see the bird's-eye view's floor.
    floor_top: i32,
    /// grid -> pixel of the floor rows (the image homography shifted up by `floor_top`).
    warp: Mat,
    grid: Size,
    close: Mat,
    grow: Option<Mat>,
    /// The opening's square: wider than any paint.
    background: Mat,
    /// The grid's cells the camera sees (the rest lies outside its image).
    seen: Mat,
    /// The floor rows in HSV on the grid, and its brightness, smoothed.
    hsv_grid: Mat,
    value: Mat,
}

fn ellipse(side: i32) -> opencv::Result<Mat> {
    imgproc::get_structuring_element_def(imgproc::MORPH_ELLIPSE, Size::new(side, side))
}

impl MaskMaker {
    pub fn new(cfg: &LaneVisionConfig, eye: &BirdsEye) -> opencv::Result<Self> {
        let floor_top = eye.floor_top_row() as i32;
        let [r0, r1, r2] = eye.grid_to_image();
        // Rows of the cropped image are rows of the image less floor_top: v' = v - top w.
        let top = f64::from(floor_top);
        let m = [r0, [0, 1, 2].map(|c| r1[c] - top * r2[c]), r2];
        let grow = cfg.glare_grow_cells as i32;
        // An odd square wider than the widest paint, in cells.
        let side = 2 * (cfg.paint_width_max / cfg.view.cell / 2.0).ceil() as i32 + 1;
        let rows = eye.intrinsics().height as i32 - floor_top;
        let whole = Mat::new_rows_cols_with_default(
            rows,
            eye.intrinsics().width as i32,
            core::CV_8UC1,
            Scalar::all(255.0),
        )?;
        let warp = Mat::from_slice_2d(&m)?;
        let grid = Size::new(eye.cols() as i32, eye.rows() as i32);
        let mut seen = Mat::default();
        imgproc::warp_perspective(
            &whole,
            &mut seen,
            &warp,
            grid,
            imgproc::INTER_NEAREST | imgproc::WARP_INVERSE_MAP,
            core::BORDER_CONSTANT,
            Scalar::all(0.0),
        )?;
        Ok(Self {
            hue: [
                cfg.yellow_hue - cfg.hue_tolerance,
                cfg.yellow_hue + cfg.hue_tolerance,
            ],
            yellow_saturation_floor: cfg.yellow_saturation_floor,
            white_saturation_ceiling: cfg.white_saturation_ceiling,
            glare_value: cfg.glare_value,
            paint_above_floor: cfg.paint_above_floor,
            floor_top,
            warp,
            grid,
            // seed 000 §2.1.3: MORPH_CLOSE with a 5x5 elliptical kernel.
            close: ellipse(5)?,
            grow: (grow > 0).then(|| ellipse(2 * grow + 1)).transpose()?,
            background: imgproc::get_structuring_element_def(
                imgproc::MORPH_RECT,
                Size::new(side, side),
            )?,
            seen,
            hsv_grid: Mat::default(),
            value: Mat::default(),
        })
    }

    /// The lane masks of `hsv` (the whole frame in HSV) with brightness floor `value_floor`.
    pub fn masks(&mut self, hsv: &Mat, value_floor: f64) -> opencv::Result<LaneMasks> {
        let floor = Rect::new(0, self.floor_top, hsv.cols(), hsv.rows() - self.floor_top);
        let roi = Mat::roi(hsv, floor)?;
        imgproc::warp_perspective(
            &roi,
            &mut self.hsv_grid,
            &self.warp,
            self.grid,
            imgproc::INTER_LINEAR | imgproc::WARP_INVERSE_MAP,
            // The image's edge carried on past it, so the edge itself is no step in the
            // floor; the cells beyond it are dropped below.
            core::BORDER_REPLICATE,
            Scalar::all(0.0),
        )?;
        let standing_out = self.standing_out()?;
        let grid = &self.hsv_grid;
        let s_white = self.white_saturation_ceiling;
        let mut yellow = Mat::default();
        // seed 000 §2.1.2: inRange(hsv, [25 - tol, max(80, s), max(100, v)], [25 + tol, 255, 255]).
        core::in_range(
            grid,
            &Scalar::new(self.hue[0], self.yellow_saturation_floor, value_floor, 0.0),
            &Scalar::new(self.hue[1], 255.0, 255.0, 0.0),
            &mut yellow,
        )?;
        // White paint: unsaturated (seed 000 §2.1.3's S <= 60), above the floor, under glare.
        let mut white = Mat::default();
        core::in_range(
            grid,
            &Scalar::new(0.0, 0.0, value_floor, 0.0),
            &Scalar::new(180.0, s_white, self.glare_value - 1.0, 0.0),
            &mut white,
        )?;
        let glare = self.glare()?;
        let (mut unglared, mut keep) = (Mat::default(), Mat::default());
        core::bitwise_not_def(&glare, &mut unglared)?;
        let mut in_view = Mat::default();
        core::bitwise_and_def(&unglared, &standing_out, &mut in_view)?;
        core::bitwise_and_def(&in_view, &self.seen, &mut keep)?;
        let (mut y, mut w) = (Mat::default(), Mat::default());
        core::bitwise_and_def(&yellow, &keep, &mut y)?;
        // The yellow tape's rim, half floor, is pale enough to pass for white: a cell
        // beside yellow paint is not white paint.
        let (mut near_yellow, mut not_near) = (Mat::default(), Mat::default());
        imgproc::dilate_def(&y, &mut near_yellow, &self.close)?;
        core::bitwise_not_def(&near_yellow, &mut not_near)?;
        let mut kept_white = Mat::default();
        core::bitwise_and_def(&white, &keep, &mut kept_white)?;
        core::bitwise_and_def(&kept_white, &not_near, &mut w)?;
        let lane_cells = (core::count_non_zero(&y)? + core::count_non_zero(&w)?) as usize;
        Ok(LaneMasks {
            yellow: y,
            white: w,
            lane_cells,
        })
    }

    /// Cells brighter than the floor around them by `paint_above_floor`: the smoothed
    /// brightness less its opening by a square wider than the paint.
    fn standing_out(&mut self) -> opencv::Result<Mat> {
        let mut channels = Vector::<Mat>::new();
        core::split(&self.hsv_grid, &mut channels)?;
        // A 3x3 mean first: the camera's noise alone never stands out.
        imgproc::blur_def(&channels.get(2)?, &mut self.value, Size::new(3, 3))?;
        let mut opened = Mat::default();
        imgproc::morphology_ex_def(
            &self.value,
            &mut opened,
            imgproc::MORPH_OPEN,
            &self.background,
        )?;
        let mut above = Mat::default();
        core::subtract_def(&self.value, &opened, &mut above)?;
        let mut out = Mat::default();
        core::in_range(
            &above,
            &Scalar::all(self.paint_above_floor),
            &Scalar::all(255.0),
            &mut out,
        )?;
        Ok(out)
    }

    /// seed 000 §2.1.3 `white_suppression_mask`: V >= 230 and S <= 60, closed with a 5x5
    /// ellipse; then grown by `glare_grow_cells` so the glare's rim, no longer bright
    /// enough to be glare but still bright, goes with it.
    fn glare(&self) -> opencv::Result<Mat> {
        let mut found = Mat::default();
        core::in_range(
            &self.hsv_grid,
            &Scalar::new(0.0, 0.0, self.glare_value, 0.0),
            &Scalar::new(180.0, self.white_saturation_ceiling, 255.0, 0.0),
            &mut found,
        )?;
        let mut closed = Mat::default();
        imgproc::morphology_ex_def(&found, &mut closed, imgproc::MORPH_CLOSE, &self.close)?;
        let Some(grow) = &self.grow else {
            return Ok(closed);
        };
        let mut grown = Mat::default();
        imgproc::dilate_def(&closed, &mut grown, grow)?;
        Ok(grown)
    }
}
