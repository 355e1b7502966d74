//! `[lane.vision]`: the lane camera pipeline's thresholds, bird's-eye view, sliding
//! windows and filters, each default a number of seed 000 §2-§3 where the seed gives one,
//! and why the pipeline could not be built.

use serde::{Deserialize, Serialize};

/// The floor patch the bird's-eye view covers, in the robot frame (x ahead, y left).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct BirdsEyeView {
    /// Nearest floor row, metres ahead of the robot's centre.
    pub near: f64,
    /// Farthest floor row, metres ahead of the robot's centre.
    pub far: f64,
    /// Metres either side of the robot's axis.
    pub half_width: f64,
    /// Side of one bird's-eye cell, metres (the fits are reported in millimetres).
    pub cell: f64,
}

impl Default for BirdsEyeView {
    /// 0.2-0.9 m ahead and 0.5 m either side: the 1 m wide view seed 000's pixel gains
    /// act on (`LaneSighting::MM_PER_PX`), sampled every 4 mm.
    fn default() -> Self {
        Self {
            near: 0.2,
            far: 0.9,
            half_width: 0.5,
            cell: 0.004,
        }
    }
}

/// How lane lines, lights and barriers are read from the lane camera's frames.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LaneVisionConfig {
    /// The yellow line's hue, OpenCV units (0-180).
    pub yellow_hue: f64,
    /// Hues within this of `yellow_hue` are yellow.
    pub hue_tolerance: f64,
    /// Least saturation of yellow lane paint.
    pub yellow_saturation_floor: f64,
    /// Most saturation of white lane paint, and of glare.
    pub white_saturation_ceiling: f64,
    /// The brightness floor of lane paint the PI loop starts from.
    pub value_floor: f64,
    /// Bounds the PI loop keeps the brightness floor within: [lowest, highest].
    pub value_floor_bounds: [f64; 2],
    /// Least brightness (V) paint has above the floor around it: above the bird's-eye
    /// view's opening by a square `paint_width_max` wide.
    pub paint_above_floor: f64,
    /// The widest paint, metres: anything bright and wider (a wall seen above the floor,
    /// lit floor between shadows) is floor to the lane masks.
    pub paint_width_max: f64,
    /// Lane cells, as fractions of the bird's-eye view, the PI loop holds the share
    /// between: [least, most].
    pub pixel_ratio_band: [f64; 2],
    /// The PI loop's gains: brightness levels per unit of ratio error [Kp, Ki].
    pub pi_gains: [f64; 2],
    /// Brightness from which low-saturation light is glare.
    pub glare_value: f64,
    /// Bird's-eye cells the glare mask is grown by, to take the glare's soft rim with it.
    pub glare_grow_cells: u32,
    pub view: BirdsEyeView,
    /// Sliding windows stacked up the bird's-eye view.
    pub windows: u32,
    /// A window's base width, millimetres of floor.
    pub window_width_mm: f64,
    /// Metres between the two lines' centres.
    pub lane_width: f64,
    /// Where the lane centre is measured, metres ahead of the robot's centre.
    pub look_ahead: f64,
    /// Most curvature a fitted line may have, 1/m.
    pub max_curvature: f64,
    /// Most a fitted line may move sideways from the filtered one in a frame, metres.
    pub max_jump: f64,
    /// Frames in the confidence-weighted filter of each line's fit.
    pub filter_frames: u32,
    /// Rows below the horizon still searched for traffic lights, pixels.
    pub horizon_margin_px: u32,
    /// Frames without a barrier after which the barrier filter forgets it.
    pub barrier_forget_frames: u32,
}

impl Default for LaneVisionConfig {
    fn default() -> Self {
        Self {
            // seed 000 §2.1.2: base_hue = 25; the tolerance is not given, 10 takes 15-35.
            yellow_hue: 25.0,
            hue_tolerance: 10.0,
            // seed 000 §2.1.2: saturation floor max(80, ..), brightness floor max(100, ..).
            yellow_saturation_floor: 80.0,
            // seed 000 §2.1.3: WHITE_SATURATION_MAX = 60.
            white_saturation_ceiling: 60.0,
            // navdeck's: the seed starts at 100, but tape under a hard shadow is darker, and
            // the floor is kept out by paint_above_floor; the loop raises the floor only
            // when more than the band passes.
            value_floor: 50.0,
            // Down to 30 so tape under a hard shadow at the dark level (x0.5 x0.45 of V 180)
            // is kept; the floor is kept out by paint_above_floor, not by this bound. Up to
            // 200, under the seed's glare threshold (§2.1.3: lanes' V 180 +- 25).
            value_floor_bounds: [30.0, 200.0],
            // navdeck's margin over the floor around the paint: the twin's tape stands 75
            // above the floor at normal light, 34 under a shadow, 17 under a shadow when
            // dark; its noise, after the 3x3 mean, 1.
            paint_above_floor: 12.0,
            // Twice the twin's 25 mm tape and TurtleBot3 AutoRace's 20-30 mm.
            paint_width_max: 0.05,
            // seed 000 §2.1.2: the loop holds lane pixels at 2-3 % of the image. navdeck
            // counts them on the bird's-eye view, where the two lines of 25 mm tape (one
            // dashed) across a 1 m view cover 3.75 %, one line alone 1.25-2.5 %. A floor
            // raised over two solid lines (5-7 %) keeps glare's rim out; one raised above
            // tape under a shadow sinks again once no line is found (`ValueLoop`).
            pixel_ratio_band: [0.01, 0.05],
            // Not given by the seed: a 1 % ratio error moves the floor 1 level at once and 2
            // more each frame it lasts, so the integral, not a kick, holds the floor.
            pi_gains: [100.0, 200.0],
            // seed 000 §2.1.3: WHITE_VALUE_THRESHOLD = 230.
            glare_value: 230.0,
            glare_grow_cells: 3,
            view: BirdsEyeView::default(),
            windows: 10,
            // seed 000 §2.2.2: base_window_width = 100 (pixels of a ~1 m wide view).
            window_width_mm: 100.0,
            lane_width: 0.4,
            look_ahead: 0.35,
            // seed 000 §2.2.1 allows 0.1 1/m for a corridor; a lane course bends far
            // tighter, so a line is refused only past a 0.2 m radius.
            max_curvature: 5.0,
            max_jump: 0.08,
            // seed 000 §2.3.2: window_size = 5.
            filter_frames: 5,
            horizon_margin_px: 20,
            barrier_forget_frames: 10,
        }
    }
}

impl LaneVisionConfig {
    /// The first field out of range: (name, value, reason).
    pub fn invalid(&self) -> Option<(&'static str, f64, &'static str)> {
        let fraction = |v: f64| v > 0.0 && v < 1.0;
        let level = |v: f64| (0.0..=255.0).contains(&v);
        let positive = |v: f64| v > 0.0 && v.is_finite();
        let [lo, hi] = self.value_floor_bounds;
        let v = &self.view;
        let checks: [(&'static str, f64, bool, &'static str); 24] = [
            (
                "yellow_hue",
                self.yellow_hue,
                (0.0..=180.0).contains(&self.yellow_hue),
                "must be 0 to 180",
            ),
            (
                "hue_tolerance",
                self.hue_tolerance,
                (1.0..=45.0).contains(&self.hue_tolerance),
                "must be 1 to 45",
            ),
            (
                "yellow_saturation_floor",
                self.yellow_saturation_floor,
                level(self.yellow_saturation_floor),
                "must be 0 to 255",
            ),
            (
                "white_saturation_ceiling",
                self.white_saturation_ceiling,
                level(self.white_saturation_ceiling),
                "must be 0 to 255",
            ),
            (
                "value_floor_bounds",
                lo,
                level(lo) && level(hi) && lo <= hi,
                "must be 0 <= lowest <= highest <= 255",
            ),
            (
                "value_floor",
                self.value_floor,
                (lo..=hi).contains(&self.value_floor),
                "must lie within value_floor_bounds",
            ),
            (
                "paint_above_floor",
                self.paint_above_floor,
                level(self.paint_above_floor),
                "must be 0 to 255",
            ),
            (
                "paint_width_max",
                self.paint_width_max,
                self.paint_width_max >= 2.0 * v.cell && self.paint_width_max <= 0.5,
                "must be two view cells to 0.5 m",
            ),
            (
                "pixel_ratio_band",
                self.pixel_ratio_band[0],
                fraction(self.pixel_ratio_band[0])
                    && fraction(self.pixel_ratio_band[1])
                    && self.pixel_ratio_band[0] <= self.pixel_ratio_band[1],
                "must be fractions over 0 and under 1, least first",
            ),
            (
                "pi_gains",
                self.pi_gains[0],
                self.pi_gains.iter().all(|g| (0.0..=1e6).contains(g)),
                "must lie in 0..=1e6",
            ),
            (
                "glare_value",
                self.glare_value,
                level(self.glare_value),
                "must be 0 to 255",
            ),
            (
                "glare_grow_cells",
                self.glare_grow_cells.into(),
                self.glare_grow_cells <= 50,
                "must be at most 50",
            ),
            (
                "view.near",
                v.near,
                v.near >= 0.0 && v.near.is_finite(),
                "must be 0 or more",
            ),
            (
                "view.far",
                v.far,
                v.far > v.near + 0.1 && v.far <= 5.0,
                "must be 0.1 m past near and at most 5",
            ),
            (
                "view.half_width",
                v.half_width,
                v.half_width >= 0.1 && v.half_width <= 3.0,
                "must be 0.1 to 3",
            ),
            (
                "view.cell",
                v.cell,
                v.cell >= 0.001 && v.cell <= 0.05,
                "must be 0.001 to 0.05",
            ),
            (
                "windows",
                self.windows.into(),
                (3..=50).contains(&self.windows),
                "must be 3 to 50",
            ),
            (
                "window_width_mm",
                self.window_width_mm,
                positive(self.window_width_mm) && self.window_width_mm <= 10000.0,
                "must be over 0 and at most 10000",
            ),
            (
                "lane_width",
                self.lane_width,
                self.lane_width > 0.05 && self.lane_width < 2.0 * v.half_width,
                "must be over 0.05 and under the view's width",
            ),
            (
                "look_ahead",
                self.look_ahead,
                (v.near..=v.far).contains(&self.look_ahead),
                "must lie within the view",
            ),
            (
                "max_curvature",
                self.max_curvature,
                positive(self.max_curvature) && self.max_curvature <= 1000.0,
                "must be over 0 and at most 1000",
            ),
            (
                "max_jump",
                self.max_jump,
                positive(self.max_jump) && self.max_jump <= 10.0,
                "must be over 0 and at most 10",
            ),
            (
                "filter_frames",
                self.filter_frames.into(),
                (1..=100).contains(&self.filter_frames),
                "must be 1 to 100",
            ),
            (
                "barrier_forget_frames",
                self.barrier_forget_frames.into(),
                (1..=1000).contains(&self.barrier_forget_frames),
                "must be 1 to 1000",
            ),
        ];
        checks
            .into_iter()
            .find(|c| !c.2)
            .map(|(name, value, _, why)| (name, value, why))
    }
}

/// Why a lane pipeline could not be built.
#[derive(Debug, thiserror::Error)]
pub enum LaneVisionError {
    #[error("lane vision: `{field}` = {value}: {reason}")]
    Field {
        field: &'static str,
        value: f64,
        reason: &'static str,
    },
    #[error("lane camera: `{field}` = {value}: {reason}")]
    Camera {
        field: &'static str,
        value: f64,
        reason: &'static str,
    },
    #[error("lane vision: the camera does not see the bird's-eye view's floor: {0}")]
    View(String),
    #[error("lane camera: {0}")]
    Setup(String),
    #[cfg(feature = "vision")]
    #[error("OpenCV: {0}")]
    OpenCv(#[from] opencv::Error),
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_defaults_are_valid_and_a_bad_field_is_named() {
        assert_eq!(LaneVisionConfig::default().invalid(), None);
        let c = LaneVisionConfig {
            look_ahead: 2.0,
            ..LaneVisionConfig::default()
        };
        assert_eq!(c.invalid().map(|f| f.0), Some("look_ahead"));
        let c: LaneVisionConfig = toml::from_str("windows = 8\n[view]\ncell = 0.005\n").unwrap();
        assert_eq!((c.windows, c.view.cell, c.view.far), (8, 0.005, 0.9));
        assert!(toml::from_str::<LaneVisionConfig>("window = 8").is_err());
    }
}
