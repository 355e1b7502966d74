//! The tag camera's pinhole view of the floor from one robot pose: each pixel's ray met
//! with the floor plane, and floor points projected back onto the image.

use crate::geometry::Pose2;
use crate::perception::intrinsics::Intrinsics;
use crate::perception::mount::Mount;
use nalgebra::{Matrix3, Rotation3, Vector3};

/// Rays steeper than this towards the floor are taken to miss it (the horizon).
const GRAZING: f64 = 1e-6;

/// The camera of one frame in the world.
#[derive(Clone, Debug)]
pub struct FloorView {
    /// The lens in the world, metres.
    lens: Vector3<f64>,
    /// Camera-to-world rotation.
    to_world: Matrix3<f64>,
    /// The world ray of pixel (u, v) is `origin + u du + v dv` (pinhole back-projection,
    /// d_c = ((u - cx) / fx, (v - cy) / fy, 1), Hartley & Zisserman eq. 6.4 inverted).
    origin: Vector3<f64>,
    du: Vector3<f64>,
    dv: Vector3<f64>,
    k: Intrinsics,
}

impl FloorView {
    pub fn new(k: &Intrinsics, mount: &Mount, pose: Pose2) -> Self {
        let to_robot = Matrix3::from_columns(&[
            mount.rotate_to_robot(Vector3::x()),
            mount.rotate_to_robot(Vector3::y()),
            mount.rotate_to_robot(Vector3::z()),
        ]);
        let yaw = *Rotation3::from_axis_angle(&Vector3::z_axis(), pose.theta).matrix();
        let to_world = yaw * to_robot;
        let lens = Vector3::new(pose.x, pose.y, 0.0) + yaw * mount.to_robot(Vector3::zeros());
        Self {
            lens,
            to_world,
            origin: to_world * Vector3::new(-k.cx / k.fx, -k.cy / k.fy, 1.0),
            du: to_world * Vector3::new(1.0 / k.fx, 0.0, 0.0),
            dv: to_world * Vector3::new(0.0, 1.0 / k.fy, 0.0),
            k: k.clone(),
        }
    }

    pub fn width(&self) -> usize {
        self.k.width as usize
    }

    pub fn height(&self) -> usize {
        self.k.height as usize
    }

    /// The world ray through pixel (`u`, `v`) (pixel centres at whole numbers).
    #[inline]
    pub fn ray(&self, u: f64, v: f64) -> Vector3<f64> {
        self.origin + u * self.du + v * self.dv
    }

    /// Where `ray` meets the floor: lens + s ray with s = -lens_z / ray_z; None when it
    /// points level or up.
    #[inline]
    pub fn floor_of(&self, ray: Vector3<f64>) -> Option<[f64; 2]> {
        (ray.z < -GRAZING).then(|| {
            let s = -self.lens.z / ray.z;
            [self.lens.x + s * ray.x, self.lens.y + s * ray.y]
        })
    }

    /// The floor along row `v` when the camera has no roll: the row's rays all fall at
    /// the same slope (the image's x axis is level), so they meet the floor at the same
    /// depth and their points are the first's plus u steps. None for a rolled camera or
    /// a row above the floor's horizon.
    pub fn row_on_floor(&self, v: f64) -> Option<([f64; 2], [f64; 2])> {
        if self.du.z.abs() > 1e-12 {
            return None;
        }
        let ray = self.ray(0.0, v);
        let start = self.floor_of(ray)?;
        let s = -self.lens.z / ray.z;
        Some((start, [s * self.du.x, s * self.du.y]))
    }

    /// The floor point seen at pixel (`u`, `v`).
    #[inline]
    pub fn floor_at(&self, u: f64, v: f64) -> Option<[f64; 2]> {
        self.floor_of(self.ray(u, v))
    }

    /// The pixel of floor point (`x`, `y`) if it is in front of the lens: p_c = R^T (p -
    /// lens), u = fx x / z + cx, v = fy y / z + cy (Hartley & Zisserman eq. 6.4).
    pub fn pixel_of(&self, x: f64, y: f64) -> Option<(f64, f64)> {
        let p = self.to_world.transpose() * (Vector3::new(x, y, 0.0) - self.lens);
        (p.z > 1e-3).then(|| self.k.project(p.x, p.y, p.z))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::perception::tag_camera::TagCameraConfig;

    #[test]
    fn a_pixels_floor_point_projects_back_onto_the_pixel() {
        let c = TagCameraConfig::default();
        let view = FloorView::new(&c.intrinsics(), &c.mount(), Pose2::new(1.0, 2.0, 0.7));
        for (u, v) in [(0.0, 0.0), (639.5, 359.5), (1279.0, 719.0), (100.0, 600.0)] {
            let [x, y] = view.floor_at(u, v).unwrap();
            let (pu, pv) = view.pixel_of(x, y).unwrap();
            assert!((pu - u).abs() < 1e-6 && (pv - v).abs() < 1e-6, "{u} {v}");
        }
        // Along a row the floor points step evenly.
        let (start, step) = view.row_on_floor(500.0).unwrap();
        let [x, y] = view.floor_at(700.0, 500.0).unwrap();
        assert!((start[0] + 700.0 * step[0] - x).abs() < 1e-12);
        assert!((start[1] + 700.0 * step[1] - y).abs() < 1e-12);
        // The image centre falls `look` ahead along the heading.
        let [x, y] = view.floor_at(639.5, 359.5).unwrap();
        let look = c.look().unwrap();
        assert!((x - (1.0 + look * 0.7f64.cos())).abs() < 1e-9);
        assert!((y - (2.0 + look * 0.7f64.sin())).abs() < 1e-9);
    }
}
