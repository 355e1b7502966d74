//! Flat convex faces drawn into the frame with a depth buffer: each face is clipped to
//! the space in front of the lens, projected, and filled a scanline at a time, a pixel
//! kept where the face is nearer than what is already there.

use super::view::{NEAR, View};
use nalgebra::Vector3;

/// A flat convex polygon in the world, of one colour.
#[derive(Clone, Debug)]
pub struct Face {
    pub points: Vec<Vector3<f64>>,
    pub bgr: [u8; 3],
    /// The side it is seen from; None for a face seen from both sides.
    pub outward: Option<Vector3<f64>>,
}

/// The frame being drawn and its depth buffer of 1 / depth (0: nothing but floor).
pub struct Canvas<'a> {
    pub pixels: &'a mut [u8],
    pub inverse_depth: &'a mut [f32],
}

/// Draws `face` as `view` sees it.
pub fn fill(canvas: &mut Canvas, view: &View, face: &Face) {
    if face.points.len() < 3 {
        return;
    }
    if let Some(n) = face.outward {
        // Back-face culling: the lens must be on the outward side of the face's plane.
        if n.dot(&(view.lens - face.points[0])) <= 0.0 {
            return;
        }
    }
    let camera: Vec<Vector3<f64>> = face.points.iter().map(|&p| view.to_camera(p)).collect();
    let clipped = clip_near(&camera);
    if clipped.len() < 3 {
        return;
    }
    // The face's plane n . p = d in the camera frame (Newell's normal, robust for any
    // planar polygon).
    let mut n = Vector3::zeros();
    for i in 0..clipped.len() {
        let (a, b) = (clipped[i], clipped[(i + 1) % clipped.len()]);
        n += Vector3::new(
            (a.y - b.y) * (a.z + b.z),
            (a.z - b.z) * (a.x + b.x),
            (a.x - b.x) * (a.y + b.y),
        );
    }
    let d = n.dot(&clipped[0]);
    if d.abs() < 1e-12 {
        return; // seen edge-on
    }
    // Along the pixel's ray r = ((u - cx) / fx, (v - cy) / fy, 1) the face lies at depth
    // z = d / (n . r): 1 / z is affine in u and v (Hartley & Zisserman 8.1's plane).
    let a = n.x / (view.fx * d);
    let b = n.y / (view.fy * d);
    let c = (n.z - n.x * view.cx / view.fx - n.y * view.cy / view.fy) / d;
    let image: Vec<(f64, f64)> = clipped.iter().map(|&p| view.project(p)).collect();
    let (top, bottom) = image
        .iter()
        .fold((f64::MAX, f64::MIN), |(t, b), p| (t.min(p.1), b.max(p.1)));
    let (w, h) = (view.width as i64, view.height as i64);
    let y0 = (top.ceil() as i64).max(0);
    let y1 = (bottom.floor() as i64).min(h - 1);
    for y in y0..=y1 {
        let yf = y as f64;
        let (mut left, mut right) = (f64::MAX, f64::MIN);
        for i in 0..image.len() {
            let (p, q) = (image[i], image[(i + 1) % image.len()]);
            if (p.1 <= yf && q.1 >= yf) || (q.1 <= yf && p.1 >= yf) {
                let x = if (q.1 - p.1).abs() < 1e-12 {
                    left = left.min(p.0.min(q.0));
                    right = right.max(p.0.max(q.0));
                    continue;
                } else {
                    p.0 + (yf - p.1) * (q.0 - p.0) / (q.1 - p.1)
                };
                left = left.min(x);
                right = right.max(x);
            }
        }
        let x0 = (left.ceil() as i64).max(0);
        let x1 = (right.floor() as i64).min(w - 1);
        let row = (y * w) as usize;
        for x in x0..=x1 {
            let depth = (a * x as f64 + b * yf + c) as f32;
            let i = row + x as usize;
            if depth > canvas.inverse_depth[i] {
                canvas.inverse_depth[i] = depth;
                canvas.pixels[3 * i..3 * i + 3].copy_from_slice(&face.bgr);
            }
        }
    }
}

/// The part of a camera-frame polygon in front of the near plane z = NEAR
/// (Sutherland-Hodgman clipping against one plane).
fn clip_near(points: &[Vector3<f64>]) -> Vec<Vector3<f64>> {
    let mut out = Vec::with_capacity(points.len() + 1);
    for i in 0..points.len() {
        let (p, q) = (points[i], points[(i + 1) % points.len()]);
        let (pin, qin) = (p.z >= NEAR, q.z >= NEAR);
        if pin {
            out.push(p);
        }
        if pin != qin {
            let t = (NEAR - p.z) / (q.z - p.z);
            out.push(p + t * (q - p));
        }
    }
    out
}
