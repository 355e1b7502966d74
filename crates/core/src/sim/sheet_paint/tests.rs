//! Painting against sampling every pixel, against OpenCV's supersampled warp, and
//! single samples against hand-worked greys.

use super::*;

/// A 7-cell marker-like sheet, 6 px a cell: a border of black, a pattern inside,
/// anti-aliased by nothing (cells are flat).
fn checker() -> Sheet {
    let (cells, cell) = (7usize, 6usize);
    let n = cells * cell;
    let mut px = vec![0u8; n * n];
    for y in 0..n {
        for x in 0..n {
            let (cx, cy) = (x / cell, y / cell);
            let inner = cx > 0 && cy > 0 && cx < cells - 1 && cy < cells - 1;
            px[y * n + x] = if inner && (cx * 3 + cy) % 2 == 0 {
                230
            } else {
                25
            };
        }
    }
    Sheet::new(n, px)
}

/// The homography taking the unit sheet square to a tilted quad in a 200 x 150 frame.
fn tilted(scale: f64, shear: f64, persp: f64) -> Homography {
    // frame -> sheet: the inverse of sheet -> frame [[a, b, c], [d, e, f], [g, h, 1]].
    let fwd = nalgebra::Matrix3::new(
        scale,
        shear * scale,
        20.0,
        -shear * scale * 0.5,
        scale,
        15.0,
        persp,
        persp * 0.5,
        1.0,
    );
    let inv = fwd.try_inverse().unwrap();
    let m = inv / inv[(2, 2)];
    [
        m[(0, 0)],
        m[(0, 1)],
        m[(0, 2)],
        m[(1, 0)],
        m[(1, 1)],
        m[(1, 2)],
        m[(2, 0)],
        m[(2, 1)],
        m[(2, 2)],
    ]
}

#[test]
fn skipping_flat_cells_gives_what_sampling_every_pixel_gives() {
    let sheet = checker();
    let (w, h) = (200, 150);
    let whole = Region::whole(w, h);
    for (scale, shear, persp, s) in [
        (3.1, 0.1, 0.0005, 4),
        (1.3, -0.3, 0.002, 4),
        (0.7, 0.2, 0.0, 3),
        (2.2, 0.0, 0.004, 1),
    ] {
        let to_sheet = tilted(scale, shear, persp);
        let mut fast = vec![140u8; w * h];
        paint(&mut fast, w, whole, &sheet, &to_sheet, s);
        let mut slow = vec![140u8; w * h];
        for y in 0..h {
            for x in 0..w {
                slow[y * w + x] = sampled(140, x, y, &sheet, &to_sheet, s);
            }
        }
        assert_eq!(
            fast, slow,
            "scale {scale} shear {shear} persp {persp} s {s}"
        );
        assert!(fast.contains(&25) && fast.contains(&230));
        // The same map scaled by -1 paints the same, once turned to face the frame.
        let flipped = facing(to_sheet.map(|v| -v), 20.0, 15.0);
        let mut again = vec![140u8; w * h];
        paint(&mut again, w, whole, &sheet, &flipped, s);
        assert_eq!(again, fast);
    }
}

/// OpenCV's supersampled warp, as the rendered camera painted before: the box drawn
/// at `s` times the resolution (what is there repeated), the sheet warped over it with
/// bilinear interpolation and a transparent border, and area-averaged back down.
fn opencv_paint(frame: &mut [u8], width: usize, sheet: &Sheet, to_sheet: &Homography, s: usize) {
    use opencv::core::{BORDER_TRANSPARENT, Mat, Scalar, Size};
    use opencv::imgproc;
    use opencv::prelude::*;
    let height = frame.len() / width;
    let n = sheet.side() as i32;
    let picture = Mat::new_rows_cols_with_data(n, n, sheet.pixels()).unwrap();
    let before = Mat::new_rows_cols_with_data(height as i32, width as i32, frame).unwrap();
    let (w, h, k) = (width as i32, height as i32, s as i32);
    let mut fine = Mat::default();
    imgproc::resize(
        &before,
        &mut fine,
        Size::new(w * k, h * k),
        0.0,
        0.0,
        imgproc::INTER_NEAREST,
    )
    .unwrap();
    // Fine pixel f is frame point (f + 0.5) / s - 0.5: fine -> sheet is to_sheet after that.
    let (a, b) = (1.0 / s as f64, 0.5 / s as f64 - 0.5);
    let scale = nalgebra::Matrix3::new(a, 0.0, b, 0.0, a, b, 0.0, 0.0, 1.0);
    let m = nalgebra::Matrix3::from_row_slice(to_sheet) * scale;
    let mut inverse_map =
        Mat::new_rows_cols_with_default(3, 3, opencv::core::CV_64F, Scalar::all(0.0)).unwrap();
    for r in 0..3 {
        for c in 0..3 {
            *inverse_map.at_2d_mut::<f64>(r as i32, c as i32).unwrap() = m[(r, c)];
        }
    }
    imgproc::warp_perspective(
        &picture,
        &mut fine,
        &inverse_map,
        Size::new(w * k, h * k),
        imgproc::INTER_LINEAR | imgproc::WARP_INVERSE_MAP,
        BORDER_TRANSPARENT,
        Scalar::default(),
    )
    .unwrap();
    let mut out = Mat::default();
    imgproc::resize(
        &fine,
        &mut out,
        Size::new(w, h),
        0.0,
        0.0,
        imgproc::INTER_AREA,
    )
    .unwrap();
    frame.copy_from_slice(out.data_bytes().unwrap());
}

#[test]
fn painting_matches_opencvs_supersampled_warp_to_a_grey_level() {
    let sheet = checker();
    let (w, h) = (200, 150);
    let whole = Region::whole(w, h);
    for (scale, shear, persp) in [(3.1, 0.1, 0.0005), (1.3, -0.3, 0.002), (0.7, 0.2, 0.0)] {
        let to_sheet = tilted(scale, shear, persp);
        let mut ours = vec![140u8; w * h];
        paint(&mut ours, w, whole, &sheet, &to_sheet, 4);
        let mut theirs = vec![140u8; w * h];
        opencv_paint(&mut theirs, w, &sheet, &to_sheet, 4);
        let diffs: Vec<i32> = ours
            .iter()
            .zip(&theirs)
            .map(|(&a, &b)| (i32::from(a) - i32::from(b)).abs())
            .collect();
        let worst = diffs.iter().max().copied().unwrap_or(0);
        let mean = diffs.iter().sum::<i32>() as f64 / diffs.len() as f64;
        let painted = theirs.iter().filter(|&&p| p != 140).count();
        eprintln!("scale {scale}: {painted} px painted, worst {worst}, mean {mean:.4}");
        assert!(painted > 500, "{painted} px painted");
        assert!(
            worst <= 1 && mean < 0.05,
            "scale {scale}: worst {worst}, mean {mean}"
        );
    }
}

#[test]
fn a_sample_is_the_bilinear_grey_and_off_the_sheet_is_nothing() {
    let sheet = Sheet::new(2, vec![0, 100, 200, 40]);
    let at = |u: f64, v: f64| sheet.sample(nearest(u * 32.0), nearest(v * 32.0));
    let grey = |u, v| at(u, v).map(|g| f64::from(g) / (STEPS * STEPS) as f64);
    assert_eq!(grey(0.5, 0.0), Some(50.0));
    assert_eq!(grey(0.0, 0.5), Some(100.0));
    assert_eq!(grey(0.5, 0.5), Some(85.0));
    assert_eq!(grey(0.25, 0.0), Some(25.0));
    assert_eq!(
        grey(1.0, 0.0),
        None,
        "the last column has no right neighbour"
    );
    assert_eq!(grey(0.99, 0.0), None, "0.99 is taken to 1");
    assert_eq!(grey(-0.01, 0.0), Some(0.0), "-0.01 is taken to 0");
    for x in [0.5, 1.5, 2.5, -0.5, -1.5, 2.4999, 7.51, -3.7, 1e9 + 0.5] {
        assert_eq!(nearest(x), x.round_ties_even() as i64, "{x}");
    }
    assert_eq!(grey(-0.1, 0.0), None);
}

#[test]
fn a_pixel_half_on_the_sheet_keeps_half_its_old_grey() {
    // A flat sheet whose usable part (u from 0 to 3) starts in the middle of pixel 0
    // and ends in the middle of pixel 3.
    let sheet = Sheet::new(4, vec![200; 16]);
    let to_sheet = [1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0];
    let mut frame = vec![100u8; 4];
    let bounds = Region::whole(4, 1);
    paint(&mut frame, 4, bounds, &sheet, &to_sheet, 4);
    assert_eq!(frame, vec![150, 200, 200, 150]);
}
