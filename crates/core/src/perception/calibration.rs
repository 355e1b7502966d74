//! Reading an OpenCV calibration file (cv::FileStorage YAML or XML, as `calibrateCamera`
//! samples write it) into `Intrinsics`.

use super::intrinsics::{CalibrationError, Intrinsics};
use opencv::core::{FileStorage, FileStorage_Mode, Mat, MatTraitConst};
use opencv::prelude::*;
use std::path::Path;

/// The seed 001 calibration shipped with navdeck.
pub const SHIPPED: &str = "config/camera_intrinsics.yml";

/// How long OpenCV may take to read a calibration file, seconds: a real one takes well
/// under a millisecond, and some malformed files send its parser into a loop it never
/// leaves (found by fuzzing OpenCV 4.6's FileStorage).
const READ_TIMEOUT: f64 = 2.0;

/// Reads `camera_matrix` (3x3), `distortion_coefficients` (4, 5, 8, 12 or 14 values),
/// `image_width` and `image_height` from an OpenCV FileStorage file. OpenCV reads it on a
/// thread of its own: a file it cannot finish within `READ_TIMEOUT` is refused (the
/// thread is left to the process's end, which a refused calibration brings soon).
pub fn load(path: &Path) -> Result<Intrinsics, CalibrationError> {
    let (send, receive) = std::sync::mpsc::channel();
    let owned = path.to_path_buf();
    std::thread::Builder::new()
        .name("navdeck-calibration".into())
        .spawn(move || {
            let _ = send.send(read(&owned));
        })
        .map_err(|e| CalibrationError::Read {
            path: path.to_path_buf(),
            message: format!("cannot start reading: {e}"),
        })?;
    receive
        .recv_timeout(std::time::Duration::from_secs_f64(READ_TIMEOUT))
        .unwrap_or_else(|_| {
            Err(CalibrationError::Read {
                path: path.to_path_buf(),
                message: format!(
                    "OpenCV did not finish reading it within {READ_TIMEOUT} s: not a well-formed FileStorage file"
                ),
            })
        })
}

/// `load`'s work, on its own thread.
fn read(path: &Path) -> Result<Intrinsics, CalibrationError> {
    let read = |message: String| CalibrationError::Read {
        path: path.to_path_buf(),
        message,
    };
    // Checked as every input file is (a regular file, not too large) before OpenCV opens
    // and reads it; nothing is read here. (OpenCV is given the file, not its bytes: from
    // memory it refuses YAML without a `%YAML` line, which it reads from a .yml file.)
    crate::data::files::check_limited(path, crate::data::files::TEXT_LIMIT)
        .map_err(|e| read(e.to_string()))?;
    let name = path
        .to_str()
        .ok_or_else(|| read("the path is not UTF-8".into()))?;
    let fs =
        FileStorage::new(name, FileStorage_Mode::READ as i32, "").map_err(|e| read(e.message))?;
    if !fs.is_opened().unwrap_or(false) {
        return Err(read("OpenCV cannot open it as FileStorage YAML/XML".into()));
    }
    let field = |field: &'static str, reason: String| CalibrationError::Field {
        path: path.to_path_buf(),
        field,
        reason,
    };
    let matrix = |key: &'static str| -> Result<Mat, CalibrationError> {
        let node = fs.get(key).map_err(|e| field(key, e.message))?;
        if node.empty().unwrap_or(true) {
            return Err(field(key, "is missing".into()));
        }
        let m = node
            .mat()
            .map_err(|_| field(key, "is not an OpenCV matrix (!!opencv-matrix)".into()))?;
        let mut d = Mat::default();
        m.convert_to(&mut d, opencv::core::CV_64F, 1.0, 0.0)
            .map_err(|e| field(key, e.message))?;
        Ok(d)
    };
    let integer = |key: &'static str| -> Result<u32, CalibrationError> {
        let node = fs.get(key).map_err(|e| field(key, e.message))?;
        if node.empty().unwrap_or(true) {
            return Err(field(key, "is missing".into()));
        }
        // OpenCV's own text is an assertion dump: say what is wrong instead.
        if !node.is_int().unwrap_or(false) {
            return Err(field(key, "is not a whole number".into()));
        }
        let v = node
            .to_i32()
            .map_err(|_| field(key, "is not a whole number".into()))?;
        u32::try_from(v).map_err(|_| field(key, format!("= {v}: must be positive")))
    };
    let k = matrix("camera_matrix")?;
    if k.rows() != 3 || k.cols() != 3 {
        return Err(field(
            "camera_matrix",
            format!("is {}x{}: must be 3x3", k.rows(), k.cols()),
        ));
    }
    let at = |r: i32, c: i32| *k.at_2d::<f64>(r, c).unwrap_or(&f64::NAN);
    let d = matrix("distortion_coefficients")?;
    let distortion: Vec<f64> = d
        .iter::<f64>()
        .map_err(|e| field("distortion_coefficients", e.message))?
        .map(|(_, v)| v)
        .collect();
    Intrinsics {
        width: integer("image_width")?,
        height: integer("image_height")?,
        fx: at(0, 0),
        fy: at(1, 1),
        cx: at(0, 2),
        cy: at(1, 2),
        distortion,
    }
    .check(path)
}

/// The configured calibration file, or seed 001's camera when none is named.
pub fn load_or_default(path: Option<&Path>) -> Result<Intrinsics, CalibrationError> {
    path.map_or_else(|| Ok(Intrinsics::default()), load)
}

/// The 3x3 camera matrix of `k` as OpenCV takes it.
pub fn camera_matrix(k: &Intrinsics) -> opencv::Result<Mat> {
    Mat::from_slice_2d(&[[k.fx, 0.0, k.cx], [0.0, k.fy, k.cy], [0.0, 0.0, 1.0]])
}

/// The distortion coefficients of `k` as a 1xN matrix.
pub fn distortion(k: &Intrinsics) -> opencv::Result<Mat> {
    Mat::from_slice(&k.distortion).and_then(|m| m.try_clone())
}
