//! The world file as written on disk (TOML). Parsing here, `build.rs` checks and assembles;
//! `world_toml.rs` writes a `World` back in this form.
//! Lengths in metres, angles in degrees, `x` east and `y` north with (0, 0) the world centre.

use super::{BlockColor, WorldError};
use serde::{Deserialize, Serialize};
use std::path::Path;
use toml::Spanned;

/// Side length of a block when the file does not give one, metres.
pub const DEFAULT_BLOCK_SIZE: f64 = 0.05;
/// Distance between a gate's two markers when the file does not give one, metres.
pub const DEFAULT_GATE_WIDTH: f64 = 0.3;

#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct WorldFile {
    pub name: Spanned<String>,
    /// `[width, height]`.
    pub size: Spanned<[f64; 2]>,
    /// `[x, y, theta_deg]`.
    pub start: Spanned<[f64; 3]>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub walls: Vec<Spanned<WallSpec>>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub obstacles: Vec<Spanned<ObstacleSpec>>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub markers: Vec<Spanned<MarkerSpec>>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub gates: Vec<Spanned<GateSpec>>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub blocks: Vec<Spanned<BlockSpec>>,
    /// A lane track on the floor (`sim::track`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub track: Option<Spanned<super::track::TrackSpec>>,
}

/// A polyline wall; `closed` joins the last point back to the first.
#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct WallSpec {
    pub points: Vec<[f64; 2]>,
    #[serde(default, skip_serializing_if = "is_false")]
    pub closed: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub markers: Option<WallMarkers>,
}

/// Markers generated along every segment of a wall.
#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct WallMarkers {
    pub first_id: u32,
    pub spacing: f64,
    #[serde(default)]
    pub side: Side,
}

/// Which face of a wall carries generated markers, seen walking from one point to the next.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Side {
    #[default]
    Left,
    Right,
    Both,
}

#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ObstacleSpec {
    pub center: [f64; 2],
    /// `[along local x, along local y]`.
    pub size: [f64; 2],
    #[serde(default)]
    pub yaw_deg: f64,
    /// Up to four ids for the faces +x, +y, -x, -y; 0 leaves a face bare.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub markers: Vec<u32>,
}

#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MarkerSpec {
    pub id: u32,
    pub x: f64,
    pub y: f64,
    pub facing_deg: f64,
}

#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct GateSpec {
    pub color: BlockColor,
    pub markers: [u32; 2],
    pub center: [f64; 2],
    pub facing_deg: f64,
    #[serde(default = "default_gate_width")]
    pub width: f64,
}

#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BlockSpec {
    pub color: BlockColor,
    pub x: f64,
    pub y: f64,
    #[serde(default)]
    pub yaw_deg: f64,
    pub markers: [u32; 2],
    #[serde(default = "default_block_size")]
    pub size: f64,
}

fn is_false(b: &bool) -> bool {
    !*b
}

fn default_gate_width() -> f64 {
    DEFAULT_GATE_WIDTH
}

fn default_block_size() -> f64 {
    DEFAULT_BLOCK_SIZE
}

/// Parses world-file text into its raw form; syntax and unknown fields fail here.
pub fn parse(text: &str, path: &Path) -> Result<WorldFile, WorldError> {
    toml::from_str(text).map_err(|e| WorldError::Parse {
        path: path.to_path_buf(),
        message: crate::data::number::shorten_long_numbers(e.to_string().trim_end()),
    })
}
