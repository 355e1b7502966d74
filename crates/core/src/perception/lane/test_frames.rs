//! Synthetic lane camera frames for the pipeline's tests: painted floors seen through the
//! camera's own geometry (each pixel's ray met with the floor), lamps drawn as lit discs
//! and barrier arms as striped polygons projected from their 3-D corners.

use super::birdseye::BirdsEye;
use super::config::BirdsEyeView;
use crate::perception::colour::BgrFrame;
use crate::perception::lane_camera::LaneCameraConfig;
use nalgebra::Vector3;
use opencv::core::{Mat, Point, Scalar, Vector};
use opencv::imgproc;
use opencv::prelude::*;

pub const FLOOR: [u8; 3] = [40, 40, 40];
pub const WALL: [u8; 3] = [70, 60, 60];
/// BGR yellow paint: hue 25, saturation 232, brightness 220.
pub const YELLOW: [u8; 3] = [20, 190, 220];
pub const WHITE: [u8; 3] = [200, 200, 200];
pub const LINE_WIDTH: f64 = 0.025;
pub const HALF_LANE: f64 = 0.2;

/// The default lane camera's geometry.
pub fn eye() -> BirdsEye {
    BirdsEye::new(&BirdsEyeView::default(), &LaneCameraConfig::default()).unwrap()
}

/// A 640x480 frame whose floor point (x ahead, y left) has colour `paint(x, y)`.
pub fn floor(paint: impl Fn(f64, f64) -> [u8; 3]) -> BgrFrame {
    let eye = eye();
    let (w, h) = (640, 480);
    let mut data = Vec::with_capacity(3 * w * h);
    for v in 0..h {
        for u in 0..w {
            let c = match eye.meet_height(u as f64, v as f64, 0.0) {
                Some(p) if p.x < 6.0 => paint(p.x, p.y),
                _ => WALL,
            };
            data.extend_from_slice(&c);
        }
    }
    BgrFrame {
        width: w,
        height: h,
        data,
    }
}

/// Paint of a lane whose lines lie `left` and `right` metres left of the robot's axis.
pub fn lines(left: Option<f64>, right: Option<f64>, lateral: f64) -> [u8; 3] {
    let on = |line: Option<f64>| line.is_some_and(|y| (lateral - y).abs() < LINE_WIDTH / 2.0);
    if on(left) {
        YELLOW
    } else if on(right) {
        WHITE
    } else {
        FLOOR
    }
}

/// A straight lane whose centre lies `offset` metres left of the robot's axis.
pub fn straight_lane(offset: f64) -> BgrFrame {
    floor(|_, y| lines(Some(offset + HALF_LANE), Some(offset - HALF_LANE), y))
}

/// A lane bending along a circle of `radius` through the robot's position, turning left
/// (radius > 0) or right (radius < 0).
pub fn curved_lane(radius: f64) -> BgrFrame {
    floor(|x, y| {
        // Offset left of the centre circle: R - |p - c| with c = (0, R), sign kept for right turns.
        let left = radius.signum() * (radius.abs() - x.hypot(y - radius));
        lines(Some(HALF_LANE), Some(-HALF_LANE), left)
    })
}

/// The frame as an OpenCV image, changed by `draw`, and back.
pub fn drawn(frame: &BgrFrame, draw: impl FnOnce(&mut Mat)) -> BgrFrame {
    let mut m = Mat::new_rows_cols_with_default(
        frame.height as i32,
        frame.width as i32,
        opencv::core::CV_8UC3,
        Scalar::all(0.0),
    )
    .unwrap();
    m.data_bytes_mut().unwrap().copy_from_slice(&frame.data);
    draw(&mut m);
    BgrFrame {
        width: frame.width,
        height: frame.height,
        data: m.data_bytes().unwrap().to_vec(),
    }
}

fn bgr(c: [u8; 3]) -> Scalar {
    Scalar::new(c[0].into(), c[1].into(), c[2].into(), 0.0)
}

/// The pixel of a robot-frame point, rounded.
fn pixel(eye: &BirdsEye, p: Vector3<f64>) -> Point {
    let (u, v) = eye.pixel_of(p).unwrap();
    Point::new(u.round() as i32, v.round() as i32)
}

/// A lamp of radius `r` metres centred at robot-frame `at`, lit `colour`, in a black box;
/// `square` draws the lit lamp as a square of the same width instead.
pub fn lamp(frame: &BgrFrame, at: Vector3<f64>, r: f64, colour: [u8; 3], square: bool) -> BgrFrame {
    let eye = eye();
    let depth = eye.mount().to_camera(at).z;
    let rp = eye.intrinsics().fx * r / depth;
    let c = pixel(&eye, at);
    drawn(frame, |m| {
        let bx = (2.0 * rp) as i32;
        let housing = opencv::core::Rect::new(c.x - bx, c.y - 4 * bx, 2 * bx, 8 * bx);
        imgproc::rectangle(
            m,
            housing,
            Scalar::all(15.0),
            imgproc::FILLED,
            imgproc::LINE_8,
            0,
        )
        .unwrap();
        if square {
            let s = rp.round() as i32;
            let rect = opencv::core::Rect::new(c.x - s, c.y - s, 2 * s, 2 * s);
            imgproc::rectangle(m, rect, bgr(colour), imgproc::FILLED, imgproc::LINE_8, 0).unwrap();
        } else {
            imgproc::circle(
                m,
                c,
                rp.round() as i32,
                bgr(colour),
                imgproc::FILLED,
                imgproc::LINE_AA,
                0,
            )
            .unwrap();
        }
    })
}

/// A barrier arm turning about `pivot` (robot frame) in the upright plane across the
/// robot, pointing left, `angle_deg` above level: `span` metres of 0.06 m stripes, red
/// from the pivot, 0.03 m thick.
pub fn arm(frame: &BgrFrame, pivot: Vector3<f64>, angle_deg: f64, span: f64) -> BgrFrame {
    let eye = eye();
    let (s, c) = angle_deg.to_radians().sin_cos();
    let along = Vector3::new(0.0, c, s);
    let across = Vector3::new(0.0, -s, c) * 0.015;
    let stripe = 0.06;
    drawn(frame, |m| {
        let mut r0 = 0.0;
        let mut red = true;
        while r0 < span - 1e-9 {
            let r1 = (r0 + stripe).min(span);
            let corners = [
                pivot + along * r0 - across,
                pivot + along * r1 - across,
                pivot + along * r1 + across,
                pivot + along * r0 + across,
            ];
            // Parts above the image's top are cut off by the fill, not by the projection.
            let pts: Vector<Point> = corners.iter().map(|&p| pixel(&eye, p)).collect();
            let colour = if red { [0, 0, 210] } else { [215, 215, 215] };
            imgproc::fill_convex_poly(m, &pts, bgr(colour), imgproc::LINE_AA, 0).unwrap();
            r0 = r1;
            red = !red;
        }
    })
}
