//! Reading Nav2 map_server maps: a YAML file naming a PGM image (ROS map_server's format,
//! "trinary" mode), so a map made for RViz and Nav2 opens here.

use super::grid::{FREE, OCCUPIED, OccupancyGrid, UNKNOWN};
use crate::geometry::Point2;
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// Why a map file was refused.
#[derive(Debug, thiserror::Error)]
pub enum MapFileError {
    #[error("cannot read map {path}: {source}")]
    Read {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("map {path}: {message}")]
    Yaml { path: PathBuf, message: String },
    #[error("map {path}: field `{field}` = {value}: {reason}")]
    Field {
        path: PathBuf,
        field: &'static str,
        value: String,
        reason: &'static str,
    },
    #[error("map image {path}: {message}")]
    Image { path: PathBuf, message: String },
}

/// The map_server YAML fields navdeck reads.
#[derive(Debug, Deserialize)]
struct MapYaml {
    image: PathBuf,
    resolution: f64,
    /// Pose of the lower-left pixel: x, y, yaw (map_server ignores yaw, and so do we).
    origin: Vec<f64>,
    #[serde(default)]
    negate: i64,
    occupied_thresh: f64,
    free_thresh: f64,
    #[serde(default)]
    mode: Option<String>,
}

/// Reads `path` (the YAML) and the image it names, relative to the YAML's folder.
pub fn load(path: &Path) -> Result<OccupancyGrid, MapFileError> {
    let text = std::fs::read_to_string(path).map_err(|source| MapFileError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    let yaml: MapYaml = serde_norway::from_str(&text).map_err(|e| MapFileError::Yaml {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    check(&yaml, path)?;
    let image_path = path.parent().unwrap_or(Path::new(".")).join(&yaml.image);
    let image = image::ImageReader::open(&image_path)
        .map_err(|source| MapFileError::Read {
            path: image_path.clone(),
            source,
        })?
        .with_guessed_format()
        .map_err(|source| MapFileError::Read {
            path: image_path.clone(),
            source,
        })?
        .decode()
        .map_err(|e| MapFileError::Image {
            path: image_path.clone(),
            message: e.to_string(),
        })?
        .to_luma8();
    let (w, h) = (image.width() as usize, image.height() as usize);
    let origin = Point2::new(yaml.origin[0], yaml.origin[1]);
    let mut grid = OccupancyGrid::new(w, h, yaml.resolution, origin, UNKNOWN);
    for (px, py, pixel) in image.enumerate_pixels() {
        let p = f64::from(pixel.0[0]);
        // map_server trinary: occupancy = (255 - p) / 255, or p / 255 when negated.
        let occupancy = if yaml.negate == 0 {
            (255.0 - p) / 255.0
        } else {
            p / 255.0
        };
        let value = if occupancy > yaml.occupied_thresh {
            OCCUPIED
        } else if occupancy < yaml.free_thresh {
            FREE
        } else {
            UNKNOWN
        };
        // Image rows run top to bottom; grid rows bottom to top.
        grid.set(px as usize, h - 1 - py as usize, value);
    }
    Ok(grid)
}

fn check(yaml: &MapYaml, path: &Path) -> Result<(), MapFileError> {
    let field = |field, value: String, reason| MapFileError::Field {
        path: path.to_path_buf(),
        field,
        value,
        reason,
    };
    if !(yaml.resolution.is_finite() && yaml.resolution > 0.0) {
        return Err(field(
            "resolution",
            yaml.resolution.to_string(),
            "must be a positive number of metres",
        ));
    }
    if yaml.origin.len() != 3 || yaml.origin.iter().any(|v| !v.is_finite()) {
        return Err(field(
            "origin",
            format!("{:?}", yaml.origin),
            "must be [x, y, yaw]",
        ));
    }
    for (name, value) in [
        ("occupied_thresh", yaml.occupied_thresh),
        ("free_thresh", yaml.free_thresh),
    ] {
        if !(0.0..=1.0).contains(&value) {
            return Err(field(name, value.to_string(), "must lie in 0..=1"));
        }
    }
    if yaml.free_thresh > yaml.occupied_thresh {
        return Err(field(
            "free_thresh",
            yaml.free_thresh.to_string(),
            "must not exceed occupied_thresh",
        ));
    }
    if let Some(mode) = &yaml.mode
        && mode != "trinary"
    {
        return Err(field(
            "mode",
            mode.clone(),
            "only map_server's trinary mode is read",
        ));
    }
    Ok(())
}
