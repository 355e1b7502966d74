//! A square marker's pose from its four corners, as the marker camera (ArUco) and the tag
//! camera (AprilTag) both measure it: OpenCV's solvePnP with IPPE_SQUARE, and how far the
//! pose's corners reproject from the ones found.

use nalgebra::{Matrix3, Vector3};
use opencv::calib3d;
use opencv::core::{Mat, Point2f, Point3f, Vector};
use opencv::prelude::*;

/// A marker's pose in the camera frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SquarePose {
    /// The marker's centre, metres (x right, y down the image, z along the axis).
    pub centre: Vector3<f64>,
    /// The marker's axes in the camera frame: x to its right, y to its top, z out of it.
    pub rotation: Matrix3<f64>,
    /// RMS distance between the corners found and the pose's reprojection, pixels.
    pub reprojection_px: f64,
}

/// The pose of a square `half` metres from centre to side whose corners (clockwise from
/// the top-left) were found at `quad`; None when solvePnP finds none.
pub fn square_pose(
    half: f64,
    quad: &Vector<Point2f>,
    camera_matrix: &Mat,
    distortion: &Mat,
) -> opencv::Result<Option<SquarePose>> {
    let h = half as f32;
    // IPPE_SQUARE's object points: corners clockwise from the top-left, z = 0, x to the
    // marker's right and y to its top (OpenCV docs, SOLVEPNP_IPPE_SQUARE).
    let object: Vector<Point3f> = Vector::from_iter([
        Point3f::new(-h, h, 0.0),
        Point3f::new(h, h, 0.0),
        Point3f::new(h, -h, 0.0),
        Point3f::new(-h, -h, 0.0),
    ]);
    let (mut rvec, mut tvec) = (Mat::default(), Mat::default());
    let solved = calib3d::solve_pnp(
        &object,
        quad,
        camera_matrix,
        distortion,
        &mut rvec,
        &mut tvec,
        false,
        calib3d::SOLVEPNP_IPPE_SQUARE,
    )?;
    if !solved {
        return Ok(None);
    }
    let mut projected: Vector<Point2f> = Vector::new();
    calib3d::project_points_def(
        &object,
        &rvec,
        &tvec,
        camera_matrix,
        distortion,
        &mut projected,
    )?;
    let sum2: f64 = (quad.iter().zip(projected.iter()))
        .map(|(seen, model)| f64::from((seen.x - model.x).powi(2) + (seen.y - model.y).powi(2)))
        .sum();
    let mut turn = Mat::default();
    calib3d::rodrigues_def(&rvec, &mut turn)?;
    let r = |i: i32, j: i32| turn.at_2d::<f64>(i, j).copied();
    let t = |i: i32| tvec.at::<f64>(i).copied();
    Ok(Some(SquarePose {
        centre: Vector3::new(t(0)?, t(1)?, t(2)?),
        rotation: Matrix3::new(
            r(0, 0)?,
            r(0, 1)?,
            r(0, 2)?,
            r(1, 0)?,
            r(1, 1)?,
            r(1, 2)?,
            r(2, 0)?,
            r(2, 1)?,
            r(2, 2)?,
        ),
        reprojection_px: (sum2 / 4.0).sqrt(),
    }))
}
