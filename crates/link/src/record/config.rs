//! `[record]`: where sessions are recorded and how much of the heavy data goes in.

use navdeck_core::data::check::{self, Invalid};
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// How chunks are compressed (MCAP's well-known compressions).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Compression {
    #[default]
    Zstd,
    Lz4,
    None,
}

impl Compression {
    /// Its name in a config file.
    pub fn name(self) -> &'static str {
        match self {
            Compression::Zstd => "zstd",
            Compression::Lz4 => "lz4",
            Compression::None => "none",
        }
    }
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RecordConfig {
    /// Record every console session into this folder, one `navdeck-DATE.mcap` each.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub folder: Option<PathBuf>,
    pub compression: Compression,
    /// The compressor's level (zstd 1..=19, lz4 1..=12). Higher levels make smaller files
    /// but their tables crowd the control loop out of the CPU's caches: zstd 9 saves 6 %
    /// of the bytes and costs the loop 6 % (`cargo bench --bench record`).
    pub level: u32,
    /// A chunk is closed (and readable after a crash) at least this often, seconds.
    pub chunk_period: f64,
    /// The occupancy grid, when it changed, at most this often, seconds (slam_toolbox's
    /// `map_update_interval` default).
    pub map_period: f64,
    /// The landmarks at most this often, and the planned path when it changed, seconds.
    pub picture_period: f64,
    /// The camera's picture at most this often, seconds; 0 records no images.
    pub image_period: f64,
}

impl Default for RecordConfig {
    fn default() -> Self {
        Self {
            folder: None,
            compression: Compression::Zstd,
            level: 3,
            chunk_period: 2.0,
            map_period: 5.0,
            picture_period: 5.0,
            image_period: 1.0,
        }
    }
}

impl RecordConfig {
    /// Checks what the parser cannot.
    pub fn validate(&self) -> Result<(), Invalid> {
        // Each compressor's own range of levels: zstd 1..=19 (its "ultra" levels above
        // need more memory than a recorder should take), lz4 frame 1..=12 (LZ4HC_CLEVEL_MAX);
        // without compression the level is unused, and kept in zstd's range.
        let most = match self.compression {
            Compression::Lz4 => 12,
            Compression::Zstd | Compression::None => 19,
        };
        if !(1..=most).contains(&self.level) {
            let reason = format!(
                "must lie in 1..={most} with compression = \"{}\"",
                self.compression.name()
            );
            return Err(("level", f64::from(self.level), reason.into()));
        }
        check::within(&[
            ("chunk_period", self.chunk_period, 0.1, 60.0),
            ("map_period", self.map_period, 0.1, 600.0),
            ("picture_period", self.picture_period, 0.1, 600.0),
            ("image_period", self.image_period, 0.0, 600.0),
        ])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_level_is_checked_against_the_compressor_chosen() {
        let with = |compression, level| {
            RecordConfig {
                compression,
                level,
                ..RecordConfig::default()
            }
            .validate()
        };
        assert_eq!(with(Compression::Zstd, 19), Ok(()));
        assert_eq!(with(Compression::Lz4, 12), Ok(()));
        let (field, value, reason) = with(Compression::Lz4, 19).unwrap_err();
        assert_eq!((field, value), ("level", 19.0));
        assert_eq!(reason, "must lie in 1..=12 with compression = \"lz4\"");
        assert_eq!(with(Compression::Zstd, 0).unwrap_err().0, "level");
        assert_eq!(with(Compression::Zstd, 20).unwrap_err().0, "level");
    }
}
