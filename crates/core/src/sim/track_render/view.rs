//! The camera's view from one robot pose: world points into the camera frame and onto
//! the image.

use crate::geometry::Pose2;
use crate::perception::intrinsics::Intrinsics;
use crate::perception::mount::Mount;
use nalgebra::{Matrix3, Rotation3, Vector3};

/// Points nearer than this in front of the lens are not drawn, metres.
pub const NEAR: f64 = 0.01;

/// World to camera for one pose: p_c = M p_w + b.
#[derive(Clone, Debug)]
pub struct View {
    m: Matrix3<f64>,
    b: Vector3<f64>,
    /// The lens in the world.
    pub lens: Vector3<f64>,
    pub fx: f64,
    pub fy: f64,
    pub cx: f64,
    pub cy: f64,
    pub width: usize,
    pub height: usize,
}

impl View {
    pub fn new(k: &Intrinsics, mount: &Mount, pose: Pose2) -> Self {
        // Camera-to-robot rotation R from the mount's images of the unit vectors.
        let r = Matrix3::from_columns(&[
            mount.rotate_to_robot(Vector3::x()),
            mount.rotate_to_robot(Vector3::y()),
            mount.rotate_to_robot(Vector3::z()),
        ]);
        let t = mount.to_robot(Vector3::zeros());
        let yaw = *Rotation3::from_axis_angle(&Vector3::z_axis(), pose.theta).matrix();
        let origin = Vector3::new(pose.x, pose.y, 0.0);
        // p_r = Rz(-theta) (p_w - o), p_c = R^T (p_r - t) (seed 001 "Step 1" inverted).
        let m = r.transpose() * yaw.transpose();
        let b = -(m * origin) - r.transpose() * t;
        Self {
            m,
            b,
            lens: origin + yaw * t,
            fx: k.fx,
            fy: k.fy,
            cx: k.cx,
            cy: k.cy,
            width: k.width as usize,
            height: k.height as usize,
        }
    }

    /// A world point in the camera frame.
    #[inline]
    pub fn to_camera(&self, p: Vector3<f64>) -> Vector3<f64> {
        self.m * p + self.b
    }

    /// The pixel of a camera-frame point: u = fx x / z + cx, v = fy y / z + cy
    /// (Hartley & Zisserman, eq. 6.4).
    #[inline]
    pub fn project(&self, p: Vector3<f64>) -> (f64, f64) {
        (self.fx * p.x / p.z + self.cx, self.fy * p.y / p.z + self.cy)
    }

    /// The pixel of a world point, if it is in front of the lens.
    pub fn pixel(&self, p: Vector3<f64>) -> Option<(f64, f64)> {
        let c = self.to_camera(p);
        (c.z > NEAR).then(|| self.project(c))
    }

    /// Whether pixel (`u`, `v`) lies inside the image.
    pub fn inside(&self, (u, v): (f64, f64)) -> bool {
        u >= -0.5 && v >= -0.5 && u < self.width as f64 - 0.5 && v < self.height as f64 - 0.5
    }
}
