//! The tag camera (seed 003 §1.2.2, §2.1): a camera on the robot looking down and ahead
//! at the AprilTags (36h11) on the floor, 1280x720 as the seed's `/rgb`. The twin renders
//! its frames (`sim::tag_render`); with the vision feature OpenCV reads them
//! (`perception::tag_detect`).

use super::config::MountConfig;
use super::intrinsics::Intrinsics;
use super::mount::Mount;
use crate::data::check::{self, Invalid};
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

/// How the detector refines a tag's corners (OpenCV's `CornerRefineMethod`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TagCornerRefinement {
    None,
    Subpix,
    /// The AprilTag library's edge fit (OpenCV's CORNER_REFINE_APRILTAG).
    Apriltag,
}

/// `[vision.tag_camera]`: the tag camera's image, lens, mount, the tags' printed size and
/// what the detector accepts.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TagCameraConfig {
    /// Image size, pixels (seed 003 §1.2.2: 1280x720).
    pub width: u32,
    pub height: u32,
    /// Horizontal field of view, degrees (square pixels, centred principal point).
    pub hfov_deg: f64,
    pub mount: MountConfig,
    /// Side of each tag's black square, metres; a white border one cell wide lies round
    /// it. A tag map's `vision.tag_size` parameter overrides it.
    pub tag_side: f64,
    pub corner_refinement: TagCornerRefinement,
    /// The adaptive threshold's window, pixels (odd): one pass with a window about a
    /// cell wide (OpenCV's default tries 3, 13 and 23 px, three passes, for markers of
    /// every size; a floor tag's cells are always 15-25 px here).
    pub threshold_window_px: u32,
    /// A tag whose corners' RMS reprojection error exceeds this is refused, pixels.
    pub max_reprojection_error_px: f64,
    /// A tag with a corner nearer the image's edge than this is refused, pixels: its
    /// border may be cut off, and with it the corner.
    pub edge_margin_px: f64,
    /// A pose that does not lie on the floor is refused: its normal more than this from
    /// straight up, degrees, or its centre more than `max_height` off the floor, metres.
    pub max_tilt_deg: f64,
    pub max_height: f64,
    /// Standard deviation of the rendered frames' pixel noise, grey levels.
    pub noise_std: f64,
}

impl Default for TagCameraConfig {
    /// 1280x720 (seed 003 §1.2.2) behind a 76° lens, 0.25 m up and 0.0559 m ahead of the
    /// robot's centre, tilted 80° down: the image centre falls on the floor 0.1 m ahead
    /// of the centre, as the ideal tag camera's does (0.0559 + 0.25 / tan 80° = 0.1000),
    /// and the view spans about 0.4 m across there and 0.23 m along, near the ideal
    /// camera's 0.4 x 0.3 m. The seed gives no tag size: navdeck's tags have a 50 mm black
    /// square (62.5 mm printed with the white border), whole in view over about 0.17 m of
    /// travel (17 frames at 0.3 m/s and 30 Hz) and about 160 px (20 px a cell) across.
    fn default() -> Self {
        Self {
            width: 1280,
            height: 720,
            hfov_deg: 76.0,
            mount: MountConfig {
                rotation_deg: [-170.0, 0.0, -90.0],
                translation: [0.0559, 0.0, 0.25],
            },
            tag_side: 0.05,
            corner_refinement: TagCornerRefinement::Subpix,
            threshold_window_px: 23,
            max_reprojection_error_px: 1.0,
            edge_margin_px: 4.0,
            max_tilt_deg: 10.0,
            max_height: 0.02,
            noise_std: 2.0,
        }
    }
}

impl TagCameraConfig {
    /// The pinhole intrinsics: fx = fy = (width / 2) / tan(hfov / 2) (Hartley & Zisserman
    /// 6.1), principal point at the centre (OpenCV's pixel centres at whole numbers), no
    /// distortion.
    pub fn intrinsics(&self) -> Intrinsics {
        let f = f64::from(self.width) / 2.0 / (self.hfov_deg.to_radians() / 2.0).tan();
        Intrinsics {
            width: self.width,
            height: self.height,
            fx: f,
            fy: f,
            cx: (f64::from(self.width) - 1.0) / 2.0,
            cy: (f64::from(self.height) - 1.0) / 2.0,
            distortion: vec![0.0; 5],
        }
    }

    pub fn mount(&self) -> Mount {
        Mount::new(&self.mount)
    }

    /// The floor point at the image centre, metres ahead of the robot's centre: where the
    /// optical axis meets the floor, lens + s axis with s = -lens_z / axis_z. None when
    /// the camera does not look down.
    pub fn look(&self) -> Option<f64> {
        let mount = self.mount();
        let lens = mount.to_robot(Vector3::zeros());
        let axis = mount.rotate_to_robot(Vector3::z());
        (axis.z < -1e-3 && lens.z > 0.0).then(|| lens.x - lens.z / axis.z * axis.x)
    }

    /// The first field out of range, named as in `[vision]`: (name, value, reason).
    pub fn validate(&self) -> Result<(), Invalid> {
        let [rx, ry, rz] = self.mount.rotation_deg;
        let [tx, ty, tz] = self.mount.translation;
        check::counts_within(&[
            ("tag_camera.width", self.width.into(), 16, 4096),
            ("tag_camera.height", self.height.into(), 16, 4096),
            (
                "tag_camera.threshold_window_px",
                self.threshold_window_px.into(),
                3,
                255,
            ),
        ])?;
        check::within(&[
            ("tag_camera.hfov_deg", self.hfov_deg, 10.0, 170.0),
            ("tag_camera.tag_side", self.tag_side, 0.005, 1.0),
            (
                "tag_camera.max_reprojection_error_px",
                self.max_reprojection_error_px,
                0.01,
                100.0,
            ),
            ("tag_camera.edge_margin_px", self.edge_margin_px, 0.0, 100.0),
            ("tag_camera.max_tilt_deg", self.max_tilt_deg, 0.0, 90.0),
            ("tag_camera.max_height", self.max_height, 0.0, 1.0),
            ("tag_camera.noise_std", self.noise_std, 0.0, 50.0),
            ("tag_camera.mount.rotation_deg[0]", rx, -360.0, 360.0),
            ("tag_camera.mount.rotation_deg[1]", ry, -360.0, 360.0),
            ("tag_camera.mount.rotation_deg[2]", rz, -360.0, 360.0),
            ("tag_camera.mount.translation[0]", tx, -2.0, 2.0),
            ("tag_camera.mount.translation[1]", ty, -2.0, 2.0),
            ("tag_camera.mount.translation[2]", tz, -2.0, 2.0),
        ])?;
        if self.look().is_none() {
            return Err((
                "tag_camera.mount",
                tz,
                "must hold the camera above the floor looking down at it".into(),
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_camera_looks_at_the_ideal_cameras_floor_point() {
        let c = TagCameraConfig::default();
        assert_eq!(c.validate(), Ok(()));
        // 0.0559 + 0.25 / tan 80° = 0.0559 + 0.04408 = 0.09998.
        let look = c.look().unwrap();
        assert!((look - 0.1).abs() < 1e-3, "{look}");
        let (k, m) = (c.intrinsics(), c.mount());
        // fx = 640 / tan 38° = 819.2.
        assert!((k.fx - 819.16).abs() < 0.05, "{}", k.fx);
        // The floor point at `look` is at the principal point.
        let p = m.to_camera(Vector3::new(look, 0.0, 0.0));
        let (u, v) = k.project(p.x, p.y, p.z);
        assert!(
            (u - k.cx).abs() < 1e-6 && (v - k.cy).abs() < 1e-6,
            "{u} {v}"
        );
        // A floor point 0.05 m further ahead is higher in the image, one to the right of
        // the robot to the image's right.
        let ahead = m.to_camera(Vector3::new(look + 0.05, 0.0, 0.0));
        assert!(k.project(ahead.x, ahead.y, ahead.z).1 < k.cy);
        let right = m.to_camera(Vector3::new(look, -0.1, 0.0));
        assert!(k.project(right.x, right.y, right.z).0 > k.cx);
    }

    #[test]
    fn a_camera_that_does_not_look_down_is_refused() {
        let mut c = TagCameraConfig::default();
        c.mount.rotation_deg = [-80.0, 0.0, -90.0];
        assert_eq!(c.validate().unwrap_err().0, "tag_camera.mount");
        let c = TagCameraConfig {
            tag_side: f64::NAN,
            ..TagCameraConfig::default()
        };
        assert_eq!(c.validate().unwrap_err().0, "tag_camera.tag_side");
    }
}
