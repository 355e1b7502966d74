//! The lane camera (seed 000 §2): a colour camera at the robot's front looking down the
//! lane, 640x480 as the seed measures it (§6.3.1). The twin renders its frames; on a real
//! robot its intrinsics come from the calibration file the vision feature reads.

use super::config::MountConfig;
use super::intrinsics::Intrinsics;
use super::mount::Mount;
use serde::{Deserialize, Serialize};

/// `[lane.camera]`: the lane camera's image, field of view, mount and rate.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LaneCameraConfig {
    pub width: u32,
    pub height: u32,
    /// Horizontal field of view, degrees (square pixels, centred principal point).
    pub hfov_deg: f64,
    pub mount: MountConfig,
    /// Frames a second.
    pub rate_hz: f64,
}

impl Default for LaneCameraConfig {
    /// 640x480 (seed 000 §6.3.1) with an 80 degree lens, 0.15 m up at the front and
    /// looking 20 degrees down: the floor is in view from 0.12 m ahead of the lens, and
    /// the view reaches 12 degrees above level, so a lamp 0.22 m up is in frame from
    /// 0.33 m away. 10 frames a second, the control period's rate.
    fn default() -> Self {
        Self {
            width: 640,
            height: 480,
            hfov_deg: 80.0,
            mount: MountConfig {
                rotation_deg: [-110.0, 0.0, -90.0],
                translation: [0.05, 0.0, 0.15],
            },
            rate_hz: 10.0,
        }
    }
}

impl LaneCameraConfig {
    /// The pinhole intrinsics: fx = fy = (width / 2) / tan(hfov / 2) (Hartley & Zisserman
    /// 6.1), principal point at the centre, no distortion.
    pub fn intrinsics(&self) -> Intrinsics {
        let f = f64::from(self.width) / 2.0 / (self.hfov_deg.to_radians() / 2.0).tan();
        Intrinsics {
            width: self.width,
            height: self.height,
            fx: f,
            fy: f,
            cx: f64::from(self.width) / 2.0 - 0.5,
            cy: f64::from(self.height) / 2.0 - 0.5,
            distortion: vec![0.0; 5],
        }
    }

    /// The lane camera of a calibrated camera `k`: its image size and horizontal field of
    /// view, 2 atan(width / 2 fx) (Hartley & Zisserman 6.1), on `base`'s mount and rate.
    /// The principal point is taken as the centre and distortion as none.
    pub fn matching(k: &Intrinsics, base: &LaneCameraConfig) -> Self {
        Self {
            width: k.width,
            height: k.height,
            hfov_deg: (2.0 * (f64::from(k.width) / 2.0 / k.fx).atan()).to_degrees(),
            ..base.clone()
        }
    }

    pub fn mount(&self) -> Mount {
        Mount::new(&self.mount)
    }

    /// The first field out of range: (name, value, reason).
    pub fn invalid(&self) -> Option<(&'static str, f64, &'static str)> {
        let sides = |v: u32| (16..=4096).contains(&v);
        if !sides(self.width) {
            return Some(("width", self.width.into(), "must be 16 to 4096 pixels"));
        }
        if !sides(self.height) {
            return Some(("height", self.height.into(), "must be 16 to 4096 pixels"));
        }
        if !(self.hfov_deg > 10.0 && self.hfov_deg < 170.0) {
            return Some(("hfov_deg", self.hfov_deg, "must be over 10 and under 170"));
        }
        if !(self.rate_hz > 0.0 && self.rate_hz <= 120.0) {
            return Some(("rate_hz", self.rate_hz, "must be over 0 and at most 120"));
        }
        let rotation = self.mount.rotation_deg.into_iter();
        if let Some(v) = rotation.into_iter().find(|v| !(-360.0..=360.0).contains(v)) {
            return Some(("mount.rotation_deg", v, "must lie in -360..=360 degrees"));
        }
        let translation = self.mount.translation.into_iter();
        if let Some(v) = translation
            .into_iter()
            .find(|v| !(-10.0..=10.0).contains(v))
        {
            return Some(("mount.translation", v, "must lie in -10..=10 m"));
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    #[test]
    fn the_default_camera_sees_the_floor_ahead_and_a_lamp_above_it() {
        let c = LaneCameraConfig::default();
        let (k, m) = (c.intrinsics(), c.mount());
        assert!((k.fx - 381.36).abs() < 0.01, "{}", k.fx);
        // A floor point 0.3 m ahead on the centre line is below the image centre.
        let p = m.to_camera(Vector3::new(0.3, 0.0, 0.0));
        let (u, v) = k.project(p.x, p.y, p.z);
        assert!((u - k.cx).abs() < 1e-6 && v > k.cy && v < 480.0, "{u} {v}");
        // A lamp 0.22 m up, 0.6 m ahead and 0.35 m right is in frame.
        let p = m.to_camera(Vector3::new(0.6, -0.35, 0.22));
        let (u, v) = k.project(p.x, p.y, p.z);
        assert!(
            (0.0..640.0).contains(&u) && (0.0..480.0).contains(&v),
            "{u} {v}"
        );
        assert!(c.invalid().is_none());
    }
}
