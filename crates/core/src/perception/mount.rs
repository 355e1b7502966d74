//! The camera on the robot: seed 001 section 2's camera-to-robot transform, and the range
//! and bearing of a point seen by the camera.

use super::config::MountConfig;
use super::intrinsics::Intrinsics;
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

impl Mount {
    /// The least distance ahead of the robot centre at which a point on the robot's
    /// centre line, `height` metres above the floor, is inside the image of camera `k`
    /// (searched in millimetre steps out to 2 m), if it comes into view at all.
    pub fn nearest_in_view(&self, k: &Intrinsics, height: f64) -> Option<f64> {
        (0..=2000).map(|mm| f64::from(mm) / 1000.0).find(|&x| {
            let p = self.to_camera(Vector3::new(x, 0.0, height));
            if p.z <= 0.0 {
                return false;
            }
            let (u, v) = k.project(p.x, p.y, p.z);
            (0.0..f64::from(k.width)).contains(&u) && (0.0..f64::from(k.height)).contains(&v)
        })
    }
}

/// How near a block can come (robot centre to block centre, metres) before its marker
/// leaves the bottom of the image of a camera `k` on `mount`: the marker's lower edge
/// (`markers.block_height - block_side / 2`) must be in view, and the marker is on the
/// block's face, half a block (`block_size / 2`) nearer than its centre. Infinite for a
/// camera that never sees a block marker on the centre line.
pub fn block_blind_distance(
    mount: &Mount,
    k: &Intrinsics,
    markers: &super::config::MarkerSizes,
    block_size: f64,
) -> f64 {
    let lower_edge = markers.block_height - markers.block_side / 2.0;
    mount
        .nearest_in_view(k, lower_edge)
        .map_or(f64::INFINITY, |face| face + block_size / 2.0)
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
    fn the_floor_just_ahead_is_below_the_view() {
        let k = Intrinsics::default();
        // Seed 001's camera, 0.28 m up and 53.4 degrees down at the image bottom
        // (34 + atan((480 - 256.84) / 634.26)): the floor comes into view at
        // 0.03 + 0.28 / tan(53.4 deg) = 0.238 m.
        let seed = Mount::new(&MountConfig::default());
        let floor = seed.nearest_in_view(&k, 0.0).unwrap();
        assert!((floor - 0.238).abs() < 0.002, "{floor}");
        // The twin's camera, 0.15 m up and 39.4 degrees down: 0.03 + 0.15 / tan(39.4 deg).
        let twin = Mount::new(&MountConfig::twin());
        let floor = twin.nearest_in_view(&k, 0.0).unwrap();
        assert!((floor - 0.212).abs() < 0.002, "{floor}");
        // 0.03 m above the lens, 2.05 degrees above the axis' 20 (atan(256.84 / 634.26) =
        // 22.05): 0.03 + 0.03 / tan(2.05 deg).
        let high = twin.nearest_in_view(&k, 0.18).unwrap();
        assert!((high - 0.868).abs() < 0.01, "{high}");
    }

    #[test]
    fn a_block_leaves_the_twin_camera_about_a_quarter_metre_ahead() {
        let markers = super::super::config::MarkerSizes::default();
        let k = Intrinsics::default();
        // The marker's lower edge 5 mm up comes into view 0.005 / tan(39.4 deg) = 6 mm
        // inside the floor's 0.212 m, and the block's centre is 25 mm behind its face.
        let twin = block_blind_distance(&Mount::new(&MountConfig::twin()), &k, &markers, 0.05);
        assert!((twin - 0.232).abs() < 0.002, "{twin}");
        // Seed 001's: 0.005 / tan(53.4 deg) = 4 mm inside its 0.238 m.
        let seed = block_blind_distance(&Mount::new(&MountConfig::default()), &k, &markers, 0.05);
        assert!((seed - 0.260).abs() < 0.002, "{seed}");
    }

    #[test]
    fn range_and_bearing_are_planar() {
        let (r, b) = range_bearing(Vector3::new(1.0, 1.0, 5.0));
        assert!((r - 2f64.sqrt()).abs() < 1e-12);
        assert!((b - std::f64::consts::FRAC_PI_4).abs() < 1e-12);
    }
}
