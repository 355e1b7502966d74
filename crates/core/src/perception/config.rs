//! The `[vision]` section: how the camera is mounted, how big the markers are, how the
//! ArUco detector is tuned and how the twin renders its camera (feature `vision`).
//!
//! The section is parsed and checked in every build, so one config file serves a build
//! with and without the feature.

use crate::perception::markers::MarkerCategory;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// The `[vision]` section of the config file.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct VisionConfig {
    /// OpenCV calibration file (FileStorage YAML with `camera_matrix`,
    /// `distortion_coefficients`, `image_width`, `image_height`); none: seed 001's camera.
    pub calibration: Option<PathBuf>,
    /// A V4L2 device (e.g. `/dev/video0`) to read frames from instead of the link's camera.
    pub device: Option<String>,
    pub mount: MountConfig,
    pub markers: MarkerSizes,
    pub detector: DetectorConfig,
    pub render: RenderConfig,
    /// The tag camera of tag-graph navigation (seed 003), `navdeck route --sim-camera`.
    pub tag_camera: super::tag_camera::TagCameraConfig,
}

/// Where the camera sits on the robot: seed 001 section 2, "Camera to Robot Transform".
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MountConfig {
    /// Rotation of the camera frame (OpenCV: x right, y down, z ahead) into the robot
    /// frame as extrinsic x, y, z angles, degrees: R = Rz(z) Ry(y) Rx(x) (seed 001: -124, 0, -90).
    pub rotation_deg: [f64; 3],
    /// Camera centre in the robot frame, metres (seed 001: 0.03, 0, 0.28).
    pub translation: [f64; 3],
}

impl Default for MountConfig {
    fn default() -> Self {
        Self {
            rotation_deg: [-124.0, 0.0, -90.0],
            translation: [0.03, 0.0, 0.28],
        }
    }
}

impl MountConfig {
    /// The twin's rendered camera: 0.15 m up, looking 20 degrees down (x -110).
    ///
    /// Seed 001's camera (fy 634.26, cy 256.84 of 480 rows) sees 22.0 degrees above its
    /// axis and 19.4 below. Seed 001's mount tilts that axis 34 degrees down from 0.28 m,
    /// for floor blocks, so the top of the view is 12 degrees below level and a 0.10 m wall,
    /// obstacle or gate marker centred 0.10 m up is whole in frame only within about
    /// 0.6 m: the filter starves and the gates are hardly ever mapped. Tilted 20 degrees
    /// down from 0.15 m, the top of the view is 2 degrees above level, so every marker
    /// whose top is at or below 0.15 m stays in frame out to the detector's range, and the
    /// bottom (39.4 degrees down) keeps a 0.025 m high block marker in sight until its
    /// face is about 0.18 m ahead of the lens, near enough for the final approach. The
    /// arena's marker heights are the twin's own choice, so this mount is too.
    pub fn twin() -> Self {
        Self {
            rotation_deg: [-110.0, 0.0, -90.0],
            translation: [0.03, 0.0, 0.15],
        }
    }
}

/// Printed side of the black square of each category's markers, and the height of their
/// centres above the floor (used by the twin's rendered camera), metres.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MarkerSizes {
    pub boundary_side: f64,
    pub obstacle_side: f64,
    pub gate_side: f64,
    pub block_side: f64,
    /// Centre height of wall, obstacle and gate markers.
    pub wall_height: f64,
    /// Centre height of block markers.
    pub block_height: f64,
}

impl Default for MarkerSizes {
    fn default() -> Self {
        Self {
            boundary_side: 0.10,
            obstacle_side: 0.10,
            gate_side: 0.10,
            block_side: 0.04,
            wall_height: 0.10,
            block_height: 0.025,
        }
    }
}

impl MarkerSizes {
    /// Side of the black square for a marker ID, metres (by seed 001's ID ranges).
    pub fn side(&self, id: u32) -> f64 {
        match MarkerCategory::of(id) {
            MarkerCategory::Boundary | MarkerCategory::Unknown => self.boundary_side,
            MarkerCategory::Obstacle => self.obstacle_side,
            MarkerCategory::RedGate | MarkerCategory::BlueGate => self.gate_side,
            MarkerCategory::RedBlock | MarkerCategory::BlueBlock => self.block_side,
        }
    }

    /// Height of a marker's centre above the floor, metres.
    pub fn height(&self, id: u32) -> f64 {
        match MarkerCategory::of(id) {
            MarkerCategory::RedBlock | MarkerCategory::BlueBlock => self.block_height,
            _ => self.wall_height,
        }
    }
}

/// How a corner found by the detector is refined (OpenCV's `CornerRefineMethod`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CornerRefinement {
    None,
    Subpix,
    Contour,
    /// cornerSubPix, then each corner moved onto the crossing of straight lines fitted to
    /// the square's edges (`perception::edge_fit`): unbiased on small markers.
    Edges,
}

/// ArUco detector parameters (OpenCV's `DetectorParameters`) and the sighting filter.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DetectorConfig {
    /// Adaptive threshold windows: from `min` to `max` pixels in steps of `step` (odd sizes).
    pub adaptive_thresh_win_size_min: i32,
    pub adaptive_thresh_win_size_max: i32,
    pub adaptive_thresh_win_size_step: i32,
    /// Smallest marker perimeter as a fraction of the image's larger side.
    pub min_marker_perimeter_rate: f64,
    pub corner_refinement: CornerRefinement,
    /// Half-size of the sub-pixel refinement window, pixels (small keeps far corners sharp).
    pub corner_refinement_win_size: i32,
    /// Pixels per cell of the unwarped marker the bits are read from.
    pub perspective_remove_pixel_per_cell: i32,
    /// Fraction of each cell's width left out on every side when its bit is read: 0.3
    /// reads the middle 40 %, clear of the blur from its neighbours, so markers of 2-3 px
    /// per cell are still read (OpenCV's default, 0.13, lost some of 16 px).
    pub perspective_remove_ignored_margin_per_cell: f64,
    /// Read every cell of a decoded marker again and refuse it unless each is clearly
    /// the colour its ID says (`perception::bit_check`): the original dictionary corrects
    /// no errors, so one misread cell is another valid ID.
    pub check_cells: bool,
    /// A marker whose black square has a side shorter than this in the image is decoded
    /// but its sighting rejected, pixels: under 2 px per cell its corners, and so its
    /// range, are no longer trustworthy (a 9 px block marker read 3 % short).
    pub min_side_px: f64,
    /// A sighting whose RMS reprojection error exceeds this is rejected, pixels.
    pub max_reprojection_error_px: f64,
    /// Sightings further than this are dropped, metres.
    pub max_range: f64,
}

impl Default for DetectorConfig {
    fn default() -> Self {
        Self {
            adaptive_thresh_win_size_min: 7,
            adaptive_thresh_win_size_max: 17,
            adaptive_thresh_win_size_step: 10,
            min_marker_perimeter_rate: 0.03,
            corner_refinement: CornerRefinement::Edges,
            corner_refinement_win_size: 2,
            perspective_remove_pixel_per_cell: 4,
            perspective_remove_ignored_margin_per_cell: 0.3,
            check_cells: true,
            min_side_px: 12.0,
            max_reprojection_error_px: 1.5,
            max_range: 4.0,
        }
    }
}

/// The twin's rendered camera: lighting and noise of the synthetic frames.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RenderConfig {
    /// Grey level of the background (walls, floor), 0-255.
    pub background: f64,
    /// Grey levels of a marker's black and white cells under full light, 0-255.
    pub black: f64,
    pub white: f64,
    /// Light falling on the scene, as a factor on every grey level (1: as configured).
    pub brightness: f64,
    /// Standard deviation of the per-pixel noise, grey levels.
    pub noise_std: f64,
    /// Where the twin's camera sits on the robot; `[vision].mount` is the real robot's.
    /// Set this to seed 001's values (x -124, z -90; 0.03, 0, 0.28) to render what the
    /// EV3's camera would see.
    pub mount: MountConfig,
}

impl Default for RenderConfig {
    fn default() -> Self {
        Self {
            background: 140.0,
            black: 25.0,
            white: 230.0,
            brightness: 1.0,
            noise_std: 3.0,
            mount: MountConfig::twin(),
        }
    }
}

impl VisionConfig {
    /// The first field that is out of range: (name in the section, value, reason).
    pub fn validate(&self) -> Result<(), crate::data::check::Invalid> {
        let m = &self.markers;
        let d = &self.detector;
        let r = &self.render;
        let (mount, rm) = (&self.mount, &r.mount);
        crate::data::check::within(&[
            ("markers.boundary_side", m.boundary_side, 0.005, 2.0),
            ("markers.obstacle_side", m.obstacle_side, 0.005, 2.0),
            ("markers.gate_side", m.gate_side, 0.005, 2.0),
            ("markers.block_side", m.block_side, 0.005, 2.0),
            ("markers.wall_height", m.wall_height, 0.0, 5.0),
            ("markers.block_height", m.block_height, 0.0, 5.0),
            (
                "detector.min_marker_perimeter_rate",
                d.min_marker_perimeter_rate,
                0.001,
                4.0,
            ),
            (
                "detector.max_reprojection_error_px",
                d.max_reprojection_error_px,
                0.01,
                100.0,
            ),
            ("detector.max_range", d.max_range, 0.01, 100.0),
            ("detector.min_side_px", d.min_side_px, 0.0, 10_000.0),
            ("render.brightness", r.brightness, 0.01, 10.0),
            ("render.noise_std", r.noise_std, 0.0, 100.0),
            (
                "mount.rotation_deg[0]",
                mount.rotation_deg[0],
                -360.0,
                360.0,
            ),
            (
                "mount.rotation_deg[1]",
                mount.rotation_deg[1],
                -360.0,
                360.0,
            ),
            (
                "mount.rotation_deg[2]",
                mount.rotation_deg[2],
                -360.0,
                360.0,
            ),
            ("mount.translation[0]", mount.translation[0], -10.0, 10.0),
            ("mount.translation[1]", mount.translation[1], -10.0, 10.0),
            ("mount.translation[2]", mount.translation[2], -10.0, 10.0),
            (
                "render.mount.rotation_deg[0]",
                rm.rotation_deg[0],
                -360.0,
                360.0,
            ),
            (
                "render.mount.rotation_deg[1]",
                rm.rotation_deg[1],
                -360.0,
                360.0,
            ),
            (
                "render.mount.rotation_deg[2]",
                rm.rotation_deg[2],
                -360.0,
                360.0,
            ),
            (
                "render.mount.translation[0]",
                rm.translation[0],
                -10.0,
                10.0,
            ),
            (
                "render.mount.translation[1]",
                rm.translation[1],
                -10.0,
                10.0,
            ),
            (
                "render.mount.translation[2]",
                rm.translation[2],
                -10.0,
                10.0,
            ),
        ])?;
        crate::data::check::counts_within(&[
            (
                "detector.adaptive_thresh_win_size_max",
                u64::try_from(d.adaptive_thresh_win_size_max).unwrap_or(0),
                3,
                1001,
            ),
            (
                "detector.corner_refinement_win_size",
                u64::try_from(d.corner_refinement_win_size).unwrap_or(0),
                1,
                100,
            ),
            (
                "detector.perspective_remove_pixel_per_cell",
                u64::try_from(d.perspective_remove_pixel_per_cell).unwrap_or(0),
                1,
                100,
            ),
        ])?;
        let grey = [
            ("render.background", r.background),
            ("render.black", r.black),
            ("render.white", r.white),
        ];
        if let Some((field, value)) = grey.into_iter().find(|(_, v)| !(0.0..=255.0).contains(v)) {
            return Err((field, value, "must lie in 0..=255".into()));
        }
        if r.white <= r.black {
            return Err(("render.white", r.white, "must be above render.black".into()));
        }
        let windows = [
            (
                "detector.adaptive_thresh_win_size_min",
                d.adaptive_thresh_win_size_min,
            ),
            (
                "detector.adaptive_thresh_win_size_max",
                d.adaptive_thresh_win_size_max,
            ),
        ];
        if let Some((field, value)) = windows.into_iter().find(|(_, v)| *v < 3) {
            return Err((field, f64::from(value), "must be at least 3 pixels".into()));
        }
        if d.adaptive_thresh_win_size_max < d.adaptive_thresh_win_size_min {
            return Err((
                "detector.adaptive_thresh_win_size_max",
                f64::from(d.adaptive_thresh_win_size_max),
                "must not be below adaptive_thresh_win_size_min".into(),
            ));
        }
        let counts = [
            (
                "detector.corner_refinement_win_size",
                d.corner_refinement_win_size,
            ),
            (
                "detector.perspective_remove_pixel_per_cell",
                d.perspective_remove_pixel_per_cell,
            ),
            (
                "detector.adaptive_thresh_win_size_step",
                d.adaptive_thresh_win_size_step,
            ),
        ];
        if let Some((field, value)) = counts.into_iter().find(|(_, v)| *v < 1) {
            return Err((field, f64::from(value), "must be at least 1".into()));
        }
        let margin = d.perspective_remove_ignored_margin_per_cell;
        if !(0.0..0.5).contains(&margin) {
            return Err((
                "detector.perspective_remove_ignored_margin_per_cell",
                margin,
                "must be from 0 to under 0.5 (of a cell, on each side)".into(),
            ));
        }
        self.tag_camera.validate()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_carry_seed_001_mount() {
        let v = VisionConfig::default();
        assert_eq!(v.validate(), Ok(()));
        assert_eq!(v.mount.rotation_deg, [-124.0, 0.0, -90.0]);
        assert_eq!(v.mount.translation, [0.03, 0.0, 0.28]);
        assert_eq!(v.render.mount, MountConfig::twin());
        assert_eq!(v.markers.side(421), 0.04);
        assert_eq!(v.markers.side(7), 0.10);
    }

    #[test]
    fn bad_values_name_their_field() {
        let mut v = VisionConfig::default();
        v.render.white = 10.0;
        assert_eq!(v.validate().unwrap_err().0, "render.white");
        let mut v = VisionConfig::default();
        v.markers.block_side = 0.0;
        assert_eq!(v.validate().unwrap_err().0, "markers.block_side");
        let mut v = VisionConfig::default();
        v.detector.adaptive_thresh_win_size_max = 5;
        assert_eq!(
            v.validate().unwrap_err().0,
            "detector.adaptive_thresh_win_size_max"
        );
    }
}
