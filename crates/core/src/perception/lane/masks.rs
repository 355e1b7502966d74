//! The lane masks (seed 000 §2.1.2-§2.1.3): yellow and white paint picked out in HSV above
//! the PI loop's brightness floor, glare taken out of both, and the two masks warped onto
//! the bird's-eye grid.

use super::birdseye::BirdsEye;
use super::config::LaneVisionConfig;
use opencv::core::{self, Mat, Rect, Scalar, Size};
use opencv::imgproc;
use opencv::prelude::*;

/// The lane masks of one frame on the bird's-eye grid, and how many image pixels passed.
pub struct LaneMasks {
    pub yellow: Mat,
    pub white: Mat,
    /// Yellow and white pixels in the image, after glare was taken out.
    pub lane_pixels: usize,
}

/// Makes lane masks for one camera: the warp and kernels built once.
pub struct MaskMaker {
    hue: [f64; 2],
    yellow_saturation_floor: f64,
    white_saturation_ceiling: f64,
    glare_value: f64,
    /// Rows from here down can see the bird's-eye view's floor.
    floor_top: i32,
    /// grid -> pixel of the floor rows (the image homography shifted up by `floor_top`).
    warp: Mat,
    grid: Size,
    close: Mat,
    grow: Option<Mat>,
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
        let grow = cfg.glare_grow_px as i32;
        Ok(Self {
            hue: [
                cfg.yellow_hue - cfg.hue_tolerance,
                cfg.yellow_hue + cfg.hue_tolerance,
            ],
            yellow_saturation_floor: cfg.yellow_saturation_floor,
            white_saturation_ceiling: cfg.white_saturation_ceiling,
            glare_value: cfg.glare_value,
            floor_top,
            warp: Mat::from_slice_2d(&m)?,
            grid: Size::new(eye.cols() as i32, eye.rows() as i32),
            // seed 000 §2.1.3: MORPH_CLOSE with a 5x5 elliptical kernel.
            close: ellipse(5)?,
            grow: (grow > 0).then(|| ellipse(2 * grow + 1)).transpose()?,
        })
    }

    /// The lane masks of `hsv` (the whole frame in HSV) with brightness floor `value_floor`.
    pub fn masks(&self, hsv: &Mat, value_floor: f64) -> opencv::Result<LaneMasks> {
        let floor = Rect::new(0, self.floor_top, hsv.cols(), hsv.rows() - self.floor_top);
        let roi = Mat::roi(hsv, floor)?;
        let s_white = self.white_saturation_ceiling;
        let mut yellow = Mat::default();
        // seed 000 §2.1.2: inRange(hsv, [25 - tol, max(80, s), max(100, v)], [25 + tol, 255, 255]).
        core::in_range(
            &roi,
            &Scalar::new(self.hue[0], self.yellow_saturation_floor, value_floor, 0.0),
            &Scalar::new(self.hue[1], 255.0, 255.0, 0.0),
            &mut yellow,
        )?;
        // White paint: unsaturated (seed 000 §2.1.3's S <= 60), above the floor, under glare.
        let mut white = Mat::default();
        core::in_range(
            &roi,
            &Scalar::new(0.0, 0.0, value_floor, 0.0),
            &Scalar::new(180.0, s_white, self.glare_value - 1.0, 0.0),
            &mut white,
        )?;
        let glare = self.glare(&roi)?;
        let mut keep = Mat::default();
        core::bitwise_not_def(&glare, &mut keep)?;
        let (mut y, mut w) = (Mat::default(), Mat::default());
        core::bitwise_and_def(&yellow, &keep, &mut y)?;
        core::bitwise_and_def(&white, &keep, &mut w)?;
        let lane_pixels = (core::count_non_zero(&y)? + core::count_non_zero(&w)?) as usize;
        Ok(LaneMasks {
            yellow: self.to_grid(&y)?,
            white: self.to_grid(&w)?,
            lane_pixels,
        })
    }

    /// The median brightness (V) of the floor rows of `hsv`, from every 4th pixel of every
    /// 4th row: the bare floor's level, since paint covers a few per cent of it.
    pub fn floor_median(&self, hsv: &Mat) -> opencv::Result<f64> {
        use opencv::prelude::*;
        let bytes = hsv.data_bytes()?;
        let cols = hsv.cols() as usize;
        let mut counts = [0u32; 256];
        let mut n = 0u32;
        for row in (self.floor_top.max(0) as usize..hsv.rows() as usize).step_by(4) {
            for col in (0..cols).step_by(4) {
                counts[usize::from(bytes[3 * (row * cols + col) + 2])] += 1;
                n += 1;
            }
        }
        let mut seen = 0;
        for (level, c) in counts.iter().enumerate() {
            seen += c;
            if 2 * seen >= n {
                return Ok(level as f64);
            }
        }
        Ok(0.0)
    }

    /// seed 000 §2.1.3 `white_suppression_mask`: V >= 230 and S <= 60, closed with a 5x5
    /// ellipse; then grown by `glare_grow_px` so the glare's rim, no longer bright enough
    /// to be glare but still bright, goes with it.
    fn glare(&self, roi: &impl core::ToInputArray) -> opencv::Result<Mat> {
        let mut found = Mat::default();
        core::in_range(
            roi,
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

    /// A floor-rows mask resampled onto the bird's-eye grid (nearest cell).
    fn to_grid(&self, mask: &Mat) -> opencv::Result<Mat> {
        let mut grid = Mat::default();
        imgproc::warp_perspective(
            mask,
            &mut grid,
            &self.warp,
            self.grid,
            imgproc::INTER_NEAREST | imgproc::WARP_INVERSE_MAP,
            core::BORDER_CONSTANT,
            Scalar::all(0.0),
        )?;
        Ok(grid)
    }
}

/// The frame's bytes as a 3-channel OpenCV image, copied into `into`.
pub fn bgr_mat(frame: &crate::perception::colour::BgrFrame, into: &mut Mat) -> opencv::Result<()> {
    let (rows, cols) = (frame.height as i32, frame.width as i32);
    if into.rows() != rows || into.cols() != cols || into.typ() != core::CV_8UC3 {
        *into = Mat::new_rows_cols_with_default(rows, cols, core::CV_8UC3, Scalar::all(0.0))?;
    }
    into.data_bytes_mut()?.copy_from_slice(&frame.data);
    Ok(())
}
