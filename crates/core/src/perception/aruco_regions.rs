//! ArUco squares found in windows of a frame rather than in all of it: what OpenCV's
//! `detectMarkers` finds on the whole frame, for every marker wholly inside a window with
//! half the largest threshold window (and 3 px, OpenCV's least distance to the border) to
//! spare round it.
//!
//! Inside such a window the search for squares sees what it sees on the whole frame: the
//! adaptive threshold of a pixel depends on the pixels within half a window of it,
//! contours are traced in whole pixels, and the limits on a square's perimeter, which
//! OpenCV gives as a fraction of the image's longer side, are turned back into the same
//! pixels for the window. The squares found are then read (`aruco_identify`) and their
//! corners refined (`cornerSubPix`) on the whole frame, in its coordinates, as
//! `detectMarkers` reads and refines them there. (With `contour` refinement, which needs
//! the traced outline, squares are read and refined in the window instead: the same
//! markers, corners that can differ in their last bits.)

use super::aruco::{Detector, VisionError, parameters};
use super::aruco_identify::identify;
use super::config::CornerRefinement;
use super::frame::GrayFrame;
use super::region::Region;
use opencv::core::{Mat, Point2f, Rect, Size, TermCriteria, TermCriteria_Type, Vector};
use opencv::prelude::*;
use opencv::{aruco, imgproc};

/// Corners (clockwise from the marker's top-left, whole-frame pixels) and ID of every
/// square decoded in `windows` of `frame`.
pub(super) fn find(
    detector: &Detector,
    frame: &GrayFrame,
    windows: &[Region],
) -> Result<Vec<(Vector<Point2f>, i32)>, VisionError> {
    let image = Mat::new_rows_cols_with_data(frame.height as i32, frame.width as i32, &frame.data)?;
    let config = &detector.config().detector;
    let whole = detector.parameters();
    // OpenCV's perimeter limits: the rate times the image's longer side, truncated.
    let longer = frame.width.max(frame.height) as f64;
    let min_px = (whole.min_marker_perimeter_rate() * longer).trunc();
    let max_px = (whole.max_marker_perimeter_rate() * longer).trunc();
    let in_window = config.corner_refinement == CornerRefinement::Contour;
    let mut local = parameters(config)?;
    if !in_window {
        // Find the squares only: a negative share of wrong border cells refuses every
        // square (read as coarsely as possible, one pixel a cell, since it is refused
        // whatever it reads), and the refused ones come back in the order found.
        local.set_max_erroneous_bits_in_border_rate(-1.0);
        local.set_perspective_remove_pixel_per_cell(1);
        local.set_corner_refinement_method(aruco::CORNER_REFINE_NONE);
    }
    let win = whole.corner_refinement_win_size();
    let criteria = TermCriteria::new(
        TermCriteria_Type::COUNT as i32 + TermCriteria_Type::EPS as i32,
        whole.corner_refinement_max_iterations(),
        whole.corner_refinement_min_accuracy(),
    )?;
    let mut found = Vec::new();
    for r in windows.iter().filter(|r| !r.is_empty()) {
        // The same limits in pixels: (n + 0.5) / side truncates back to n.
        let side = r.width().max(r.height()) as f64;
        local.set_min_marker_perimeter_rate((min_px + 0.5) / side);
        local.set_max_marker_perimeter_rate((max_px + 0.5) / side);
        let roi = Mat::roi(
            &image,
            Rect::new(
                r.x0 as i32,
                r.y0 as i32,
                r.width() as i32,
                r.height() as i32,
            ),
        )?;
        let mut corners: Vector<Vector<Point2f>> = Vector::new();
        let mut ids: Vector<i32> = Vector::new();
        let mut squares: Vector<Vector<Point2f>> = Vector::new();
        aruco::detect_markers(
            &roi,
            detector.dictionary(),
            &mut corners,
            &mut ids,
            &local,
            &mut squares,
        )?;
        // Whole pixels before refinement, so the shift is exact.
        let shift = |quad: Vector<Point2f>| -> Vector<Point2f> {
            quad.iter()
                .map(|c| Point2f::new(c.x + r.x0 as f32, c.y + r.y0 as f32))
                .collect()
        };
        if in_window {
            found.extend(corners.iter().map(shift).zip(ids.iter()));
            continue;
        }
        for square in squares.iter().map(shift) {
            let Some((id, mut quad)) = identify(&image, &square, detector.dictionary(), whole)?
            else {
                continue;
            };
            if config.corner_refinement != CornerRefinement::None {
                imgproc::corner_sub_pix(
                    &image,
                    &mut quad,
                    Size::new(win, win),
                    Size::new(-1, -1),
                    criteria,
                )?;
            }
            found.push((quad, id));
        }
    }
    Ok(found)
}
