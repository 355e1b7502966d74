//! Pinhole camera intrinsics and lens distortion, from an OpenCV calibration file or the
//! built-in seed 001 camera.

use std::path::PathBuf;

/// The camera model OpenCV's `calibrateCamera` produces.
#[derive(Clone, Debug, PartialEq)]
pub struct Intrinsics {
    pub width: u32,
    pub height: u32,
    pub fx: f64,
    pub fy: f64,
    pub cx: f64,
    pub cy: f64,
    /// k1, k2, p1, p2[, k3, ...] as OpenCV orders them.
    pub distortion: Vec<f64>,
}

impl Default for Intrinsics {
    /// Seed 001 "Camera Calibration": fx 635.93, fy 634.26, cx 444.27, cy 256.84 at 864x480;
    /// the seed gives no distortion values, so none.
    fn default() -> Self {
        Self {
            width: 864,
            height: 480,
            fx: 635.93,
            fy: 634.26,
            cx: 444.27,
            cy: 256.84,
            distortion: vec![0.0; 5],
        }
    }
}

/// Why a calibration file was refused.
#[derive(Debug, thiserror::Error)]
pub enum CalibrationError {
    #[error("calibration {path}: {message}")]
    Read { path: PathBuf, message: String },
    #[error("calibration {path}: field `{field}` {reason}")]
    Field {
        path: PathBuf,
        field: &'static str,
        reason: String,
    },
}

/// Most pixels along either side of a calibrated image, and of any camera image read.
pub const MAX_SIDE: u32 = 16_384;

impl Intrinsics {
    /// Pixel of a camera-frame point (ideal pinhole, no distortion):
    /// u = fx x / z + cx, v = fy y / z + cy (Hartley & Zisserman, eq. 6.4).
    pub fn project(&self, x: f64, y: f64, z: f64) -> (f64, f64) {
        (self.fx * x / z + self.cx, self.fy * y / z + self.cy)
    }

    /// Checks values a file could get wrong; `path` names the file in the error.
    pub fn check(self, path: &std::path::Path) -> Result<Self, CalibrationError> {
        let bad = |field: &'static str, reason: String| CalibrationError::Field {
            path: path.to_path_buf(),
            field,
            reason,
        };
        // Bounds: a camera of at most 16384 pixels a side, its focal lengths from a
        // fish-eye's (a tenth of the width) to a long lens's (a hundred widths), its
        // principal point inside the image.
        if !(1..=MAX_SIDE).contains(&self.width) || !(1..=MAX_SIDE).contains(&self.height) {
            return Err(bad(
                "image_width/image_height",
                format!(
                    "= {}x{}: each must lie in 1..={MAX_SIDE}",
                    self.width, self.height
                ),
            ));
        }
        let (w, h) = (f64::from(self.width), f64::from(self.height));
        for (field, v, lo, hi) in [
            ("camera_matrix fx", self.fx, 0.1 * w, 100.0 * w),
            ("camera_matrix fy", self.fy, 0.1 * h, 100.0 * h),
            ("camera_matrix cx", self.cx, 0.0, w),
            ("camera_matrix cy", self.cy, 0.0, h),
        ] {
            if !(lo..=hi).contains(&v) {
                return Err(bad(field, format!("= {v:?}: must lie in {lo}..={hi}")));
            }
        }
        if let Some(v) = self
            .distortion
            .iter()
            .find(|v| !(-1000.0..=1000.0).contains(*v))
        {
            return Err(bad(
                "distortion_coefficients",
                format!("hold {v:?}: each must lie in -1000..=1000"),
            ));
        }
        if ![4, 5, 8, 12, 14].contains(&self.distortion.len()) {
            return Err(bad(
                "distortion_coefficients",
                format!(
                    "has {} values: OpenCV takes 4, 5, 8, 12 or 14",
                    self.distortion.len()
                ),
            ));
        }
        Ok(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn principal_point_projects_to_cx_cy_and_one_metre_right_by_fx() {
        let k = Intrinsics::default();
        assert_eq!(k.project(0.0, 0.0, 2.0), (444.27, 256.84));
        let (u, _) = k.project(1.0, 0.0, 1.0);
        assert!((u - (444.27 + 635.93)).abs() < 1e-9);
    }

    #[test]
    fn bad_values_name_the_field() {
        let k = Intrinsics {
            fx: -1.0,
            ..Intrinsics::default()
        };
        let e = k
            .check(std::path::Path::new("cam.yml"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("cam.yml") && e.contains("fx") && e.contains("-1"),
            "{e}"
        );
    }
}
