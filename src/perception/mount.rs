//! The camera on the robot: seed 001 section 2's camera-to-robot transform, and the range
//! and bearing of a point seen by the camera.

use super::config::MountConfig;
use nalgebra::{Matrix3, Rotation3, Vector3};

/// Rigid transform from the camera frame (OpenCV: x right, y down, z ahead) to the robot
/// frame (REP-103: x ahead, y left, z up).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mount {
    rotation: Matrix3<f64>,
    translation: Vector3<f64>,
}

impl Mount {
    pub fn new(cfg: &MountConfig) -> Self {
        let [x, y, z] = cfg.rotation_deg.map(f64::to_radians);
        // Extrinsic x-y-z Euler angles: R = Rz Ry Rx (seed 001 section 2, "Rotation: (x, y, z)").
        let rotation = Rotation3::from_axis_angle(&Vector3::z_axis(), z)
            * Rotation3::from_axis_angle(&Vector3::y_axis(), y)
            * Rotation3::from_axis_angle(&Vector3::x_axis(), x);
        Self {
            rotation: *rotation.matrix(),
            translation: Vector3::from(cfg.translation),
        }
    }

    /// A camera-frame point in the robot frame: p_r = R p_c + t (seed 001 "Step 1").
    pub fn to_robot(&self, p: Vector3<f64>) -> Vector3<f64> {
        self.rotation * p + self.translation
    }

    /// A robot-frame point in the camera frame: p_c = R^T (p_r - t).
    pub fn to_camera(&self, p: Vector3<f64>) -> Vector3<f64> {
        self.rotation.transpose() * (p - self.translation)
    }

    /// A direction in the camera frame turned into the robot frame.
    pub fn rotate_to_robot(&self, v: Vector3<f64>) -> Vector3<f64> {
        self.rotation * v
    }
}

/// Seed 001's measurement of a point in the robot frame: planar range from the robot
/// centre, metres, and bearing from the heading, radians, CCW positive.
pub fn range_bearing(p: Vector3<f64>) -> (f64, f64) {
    // Seed 001 section 3: r = sqrt(dx^2 + dy^2), alpha = atan2(dy, dx).
    (p.x.hypot(p.y), p.y.atan2(p.x))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed_mount_looks_ahead_and_34_degrees_down() {
        let m = Mount::new(&MountConfig::default());
        let axis = m.rotate_to_robot(Vector3::z());
        // Hand-worked: Rz(-90) Rx(-124) (0, 0, 1) = (sin 124, 0, cos 124).
        assert!(
            (axis - Vector3::new(0.8290, 0.0, -0.5592)).norm() < 1e-4,
            "{axis}"
        );
        // Image right (camera x) is the robot's right (-y).
        let right = m.rotate_to_robot(Vector3::x());
        assert!(
            (right - Vector3::new(0.0, -1.0, 0.0)).norm() < 1e-12,
            "{right}"
        );
        // The camera centre is the mount's translation.
        assert!((m.to_robot(Vector3::zeros()) - Vector3::new(0.03, 0.0, 0.28)).norm() < 1e-12);
        let p = Vector3::new(1.0, 0.5, 0.1);
        assert!((m.to_robot(m.to_camera(p)) - p).norm() < 1e-12);
    }

    #[test]
    fn range_and_bearing_are_planar() {
        let (r, b) = range_bearing(Vector3::new(1.0, 1.0, 5.0));
        assert!((r - 2f64.sqrt()).abs() < 1e-12);
        assert!((b - std::f64::consts::FRAC_PI_4).abs() < 1e-12);
    }
}
