//! How the planning map is built from landmarks and scans (seed 001 section 4).

use serde::{Deserialize, Serialize};

/// The `[map]` section of the config file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MapConfig {
    /// Cell side, metres (seed 001: 0.01).
    pub resolution: f64,
    /// Extent centred on the origin, metres (seed 001: 4 x 4); a larger twin world wins.
    pub width: f64,
    pub height: f64,
    /// Boundary, gate and obstacle markers: radius of the 0.7 region (seed 001: 0.30 m for
    /// boundary and obstacle markers; including gates is navdeck's choice).
    pub obstacle_inflation: f64,
    /// Blocks: radius of the 0.7 region (seed 001: 0.25 m).
    pub block_inflation: f64,
    /// Around a wall or obstacle marker, the radius no plan may enter: the robot's
    /// footprint plus the landmark's own uncertainty, metres.
    pub lethal_radius: f64,
    /// Around a block, the radius no plan may enter, metres.
    pub block_lethal_radius: f64,
    /// Beyond the 0.7 region the cost falls linearly to zero over this distance, metres.
    pub gradient: f64,
    /// Boundary markers with consecutive IDs closer than this are joined into a wall
    /// (seed 001: boundary markers line the arena's perimeter), metres.
    pub wall_join: f64,
    /// Log-odds added by a lidar hit and by a beam passing through (Thrun et al.,
    /// Probabilistic Robotics, table 9.1: l = log(p / (1 - p)), here p 0.7 and 0.4).
    pub hit_log_odds: f32,
    pub miss_log_odds: f32,
    /// Exploration saves the map to `autosave.yaml` in the maps folder this often,
    /// seconds (seed 001 saves maps during exploration); 0 turns it off.
    pub autosave_every: f64,
}

impl Default for MapConfig {
    fn default() -> Self {
        Self {
            resolution: 0.01,
            width: 4.0,
            height: 4.0,
            obstacle_inflation: 0.30,
            block_inflation: 0.25,
            lethal_radius: 0.15,
            block_lethal_radius: 0.05,
            gradient: 0.20,
            wall_join: 0.75,
            hit_log_odds: 0.85,
            miss_log_odds: -0.4,
            autosave_every: 30.0,
        }
    }
}

/// Most cells a planning map may have: 16 million (a 40 m square at 1 cm), a few
/// hundred megabytes over all its layers.
pub const MAX_CELLS: f64 = 16.0e6;

impl MapConfig {
    /// The first field that is out of range: (name in the section, value, reason).
    pub fn validate(&self) -> Result<(), crate::data::check::Invalid> {
        crate::data::check::within(&[
            ("resolution", self.resolution, 0.005, 1.0),
            ("width", self.width, 0.1, 200.0),
            ("height", self.height, 0.1, 200.0),
            ("obstacle_inflation", self.obstacle_inflation, 0.001, 5.0),
            ("block_inflation", self.block_inflation, 0.001, 5.0),
            ("hit_log_odds", f64::from(self.hit_log_odds), 0.01, 10.0),
            ("miss_log_odds", f64::from(self.miss_log_odds), -10.0, -0.01),
            ("lethal_radius", self.lethal_radius, 0.0, 5.0),
            ("block_lethal_radius", self.block_lethal_radius, 0.0, 5.0),
            ("gradient", self.gradient, 0.0, 5.0),
            ("wall_join", self.wall_join, 0.0, 10.0),
            ("autosave_every", self.autosave_every, 0.0, 86_400.0),
        ])?;
        if self.cells_over((self.width, self.height)).is_some() {
            return Err((
                "resolution",
                self.resolution,
                "makes more than 16 million cells".into(),
            ));
        }
        Ok(())
    }

    /// The cells of a planning map covering `extent` metres (and at least the configured
    /// width and height) at this resolution, when they are over `MAX_CELLS`.
    fn cells_over(&self, extent: (f64, f64)) -> Option<f64> {
        let res = self.resolution;
        let cells = (extent.0.max(self.width) / res) * (extent.1.max(self.height) / res);
        // Not a number (a NaN extent) is over too.
        (cells.is_nan() || cells > MAX_CELLS).then_some(cells)
    }

    /// Whether a planning map covering `extent` metres fits within `MAX_CELLS` at
    /// `[map] resolution`: the one check for every map a session plans on (a world, an
    /// MCL map), made before anything of that size is allocated.
    pub fn check_extent(&self, extent: (f64, f64)) -> Result<(), String> {
        match self.cells_over(extent) {
            None => Ok(()),
            Some(cells) => {
                let millions = cells / 1e6;
                // Short, as 1e308 and not 300 digits.
                let shown = if millions < 1e9 {
                    format!("{millions:.0}")
                } else {
                    format!("{millions:e}")
                };
                Err(format!(
                    "{:?} x {:?} m at [map] resolution {:?} m makes {shown} million cells, over \
                     the limit of {:.0} million: use a coarser resolution",
                    extent.0.max(self.width),
                    extent.1.max(self.height),
                    self.resolution,
                    MAX_CELLS / 1e6
                ))
            }
        }
    }
}
