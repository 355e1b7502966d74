//! Reads the ID of a candidate square as OpenCV 4.6's `detectMarkers` reads it
//! (`_identifyOneCandidate` in the aruco module): the square unwarped to a few pixels a
//! cell with nearest-pixel sampling, thresholded by Otsu's method, each cell's majority
//! taken, the border checked, and the inner bits looked up in the dictionary.
//!
//! OpenCV's nearest-pixel unwarp depends on the square's corners to the last bit, so the
//! same square read in a window of a frame (corners shifted by the window's corner) can
//! come out differently from the whole frame. Reading it here, in whole-frame
//! coordinates with the same calls in the same order, gives exactly what the whole
//! frame gives.

use opencv::core::{Mat, Point2f, Ptr, Rect, Scalar, Size, Vector};
use opencv::prelude::*;
use opencv::{aruco, imgproc};

/// The ID of the square with corners `corners` (clockwise, whole-frame pixels) in
/// `image`, and the corners turned to start at the marker's top-left; `None` when it is
/// not a marker of `dictionary`.
pub(super) fn identify(
    image: &impl opencv::core::ToInputArray,
    corners: &Vector<Point2f>,
    dictionary: &Ptr<aruco::Dictionary>,
    params: &Ptr<aruco::DetectorParameters>,
) -> opencv::Result<Option<(i32, Vector<Point2f>)>> {
    let size = dictionary.marker_size();
    let border = params.marker_border_bits();
    let bits = extract_bits(image, corners, size, border, params)?;
    let allowed = (f64::from(size * size) * params.max_erroneous_bits_in_border_rate()) as i32;
    if border_errors(&bits, size, border)? > allowed {
        return Ok(None);
    }
    let cells = bits.cols();
    let inner = bits
        .row_range(&opencv::core::Range::new(border, cells - border)?)?
        .col_range(&opencv::core::Range::new(border, cells - border)?)?
        .try_clone()?;
    let (mut id, mut rotation) = (0, 0);
    if !dictionary.identify(
        &inner,
        &mut id,
        &mut rotation,
        params.error_correction_rate(),
    )? {
        return Ok(None);
    }
    // std::rotate(begin, begin + 4 - rotation, end), as OpenCV's correctCornerPosition.
    let turned = (0..4)
        .map(|k| corners.get((k + 4 - rotation as usize) % 4))
        .collect::<opencv::Result<Vector<Point2f>>>()?;
    Ok(Some((id, turned)))
}

/// The cells of the square, border included, 1 for white: OpenCV's `_extractBits`.
fn extract_bits(
    image: &impl opencv::core::ToInputArray,
    corners: &Vector<Point2f>,
    size: i32,
    border: i32,
    params: &Ptr<aruco::DetectorParameters>,
) -> opencv::Result<Mat> {
    let cell = params.perspective_remove_pixel_per_cell();
    let margin = (params.perspective_remove_ignored_margin_per_cell() * f64::from(cell)) as i32;
    let cells = size + 2 * border;
    let side = cells * cell;
    let last = (side - 1) as f32;
    let square = [
        Point2f::new(0.0, 0.0),
        Point2f::new(last, 0.0),
        Point2f::new(last, last),
        Point2f::new(0.0, last),
    ];
    let from: [Point2f; 4] = [
        corners.get(0)?,
        corners.get(1)?,
        corners.get(2)?,
        corners.get(3)?,
    ];
    let transform = imgproc::get_perspective_transform_slice_def(&from, &square)?;
    let mut unwarped = Mat::default();
    imgproc::warp_perspective(
        image,
        &mut unwarped,
        &transform,
        Size::new(side, side),
        imgproc::INTER_NEAREST,
        opencv::core::BORDER_CONSTANT,
        Scalar::default(),
    )?;
    let mut bits =
        Mat::new_rows_cols_with_default(cells, cells, opencv::core::CV_8UC1, Scalar::all(0.0))?;
    // Too even for Otsu's threshold: all one colour.
    let inner = Mat::roi(
        &unwarped,
        Rect::new(
            cell / 2,
            cell / 2,
            side - 2 * (cell / 2),
            side - 2 * (cell / 2),
        ),
    )?;
    let (mut mean, mut deviation) = (Mat::default(), Mat::default());
    opencv::core::mean_std_dev(&inner, &mut mean, &mut deviation, &opencv::core::no_array())?;
    if *deviation.at::<f64>(0)? < params.min_otsu_std_dev() {
        let all = if *mean.at::<f64>(0)? > 127.0 {
            1.0
        } else {
            0.0
        };
        bits.set_to_def(&Scalar::all(all))?;
        return Ok(bits);
    }
    let mut binary = Mat::default();
    imgproc::threshold(
        &unwarped,
        &mut binary,
        125.0,
        255.0,
        imgproc::THRESH_BINARY | imgproc::THRESH_OTSU,
    )?;
    let inside = (cell - 2 * margin) as usize;
    let (pixels, side) = (binary.data_bytes()?, side as usize);
    for y in 0..cells {
        for x in 0..cells {
            // The pixels of the cell less its margin that are not zero, as countNonZero.
            let (x0, y0) = ((x * cell + margin) as usize, (y * cell + margin) as usize);
            let white = (y0..y0 + inside)
                .map(|row| {
                    let start = row * side + x0;
                    pixels[start..start + inside]
                        .iter()
                        .filter(|&&p| p != 0)
                        .count()
                })
                .sum::<usize>();
            // More than half the pixels white (the total halved in whole numbers).
            if white > (inside * inside) / 2 {
                *bits.at_2d_mut::<u8>(y, x)? = 1;
            }
        }
    }
    Ok(bits)
}

/// White cells in the border: OpenCV's `_getBorderErrors`.
fn border_errors(bits: &Mat, size: i32, border: i32) -> opencv::Result<i32> {
    let cells = size + 2 * border;
    let mut errors = 0;
    for y in 0..cells {
        for k in 0..border {
            errors += i32::from(*bits.at_2d::<u8>(y, k)? != 0);
            errors += i32::from(*bits.at_2d::<u8>(y, cells - 1 - k)? != 0);
        }
    }
    for x in border..cells - border {
        for k in 0..border {
            errors += i32::from(*bits.at_2d::<u8>(k, x)? != 0);
            errors += i32::from(*bits.at_2d::<u8>(cells - 1 - k, x)? != 0);
        }
    }
    Ok(errors)
}
