//! Map files: a Nav2 map_server pair, `NAME.yaml` + `NAME.pgm`, so that a map saved here
//! opens in RViz and Nav2 and a Nav2 map opens here. navdeck's own extras (landmarks, the
//! robot's pose) ride in the same YAML under the `navdeck` key, which map_server ignores.

use super::grid::OccupancyGrid;
use super::pgm::{self, PgmError};
use super::raw_map::Reading;
use super::raw_map::{Mode, RawMap};
use crate::geometry::Point2;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Why a map file could not be read or written; each names the file and what is wrong.
#[derive(Debug, thiserror::Error)]
pub enum MapFileError {
    // The I/O error is part of the message, not a chained source, so it prints once.
    #[error("cannot read map {path}: {}", io_reason(error))]
    Read {
        path: PathBuf,
        error: std::io::Error,
    },
    #[error("cannot write map {path}: {}", io_reason(error))]
    Write {
        path: PathBuf,
        error: std::io::Error,
    },
    #[error("map {path}: {message}")]
    Yaml { path: PathBuf, message: String },
    #[error("map {path}{}: field `{field}` = {value}: {reason}", line.map(|l| format!(":{l}")).unwrap_or_default())]
    Field {
        path: PathBuf,
        /// The line that sets the field, when the file sets it.
        line: Option<usize>,
        field: &'static str,
        value: String,
        reason: &'static str,
    },
    #[error("map image {path}: {error}")]
    Image { path: PathBuf, error: PgmError },
}

impl MapFileError {
    /// What is wrong, without the map file's name: for a message that names the file
    /// itself ("cannot use map X as a world: …").
    pub fn reason(&self) -> String {
        match self {
            MapFileError::Read { error, .. } => format!("cannot read it: {}", io_reason(error)),
            MapFileError::Write { error, .. } => format!("cannot write it: {}", io_reason(error)),
            MapFileError::Yaml { message, .. } => message.clone(),
            MapFileError::Field {
                line,
                field,
                value,
                reason,
                ..
            } => field_reason(*line, field, value, reason),
            MapFileError::Image { path, error } => format!("its image {}: {error}", path.display()),
        }
    }
}

/// A bad field as a user reads it, without the file's name: `line 3: field `x` = 5: …`.
pub fn field_reason(line: Option<usize>, field: &str, value: &str, reason: &str) -> String {
    let at = line.map(|l| format!("line {l}: ")).unwrap_or_default();
    format!("{at}field `{field}` = {value}: {reason}")
}

/// A YAML parser's message without the text it quotes from the file (`invalid type:
/// string "root:x:0:0:…"`): an error names what is wrong, and never shows a file that was
/// not a map (one a recording pointed at, say).
fn without_quoted_text(message: &str) -> String {
    if message.starts_with("invalid type: string") && message.contains("expected struct") {
        return "not a map YAML: the file reads as one piece of text, not the fields \
                image, resolution, origin, …"
            .to_string();
    }
    let mut out = String::with_capacity(message.len());
    let mut quoted = false;
    for c in message.chars() {
        match (c, quoted) {
            ('"', false) => {
                quoted = true;
                out.push_str("\"…");
            }
            ('"', true) => {
                quoted = false;
                out.push('"');
            }
            (_, false) => out.push(c),
            (_, true) => {}
        }
    }
    out
}

/// An I/O error as a user reads it: what is wrong with the file, without the OS's
/// "(os error 2)".
pub fn io_reason(error: &std::io::Error) -> String {
    use std::io::ErrorKind;
    match error.kind() {
        ErrorKind::NotFound => "there is no such file".to_string(),
        ErrorKind::PermissionDenied => "permission denied".to_string(),
        ErrorKind::IsADirectory => "it is a folder, not a file".to_string(),
        _ => {
            let text = error.to_string();
            let text = text.split(" (os error").next().unwrap_or(&text);
            let mut chars = text.chars();
            chars.next().map_or_else(String::new, |first| {
                first.to_lowercase().chain(chars).collect()
            })
        }
    }
}

/// A landmark as saved: enough to seed the filter with it later.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SavedLandmark {
    pub id: u32,
    pub category: String,
    pub mean: [f64; 2],
    /// Row-major 2x2 covariance, m^2.
    pub covariance: [[f64; 2]; 2],
    pub sightings: u32,
}

/// A block as saved: colour, its two markers, centre, and whether both markers were seen.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SavedBlock {
    pub colour: String,
    pub markers: [u32; 2],
    pub position: [f64; 2],
    pub confirmed: bool,
}

/// A gate as saved: colour, its two markers, centre and the normal into the arena.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SavedGate {
    pub colour: String,
    pub markers: [u32; 2],
    pub center: [f64; 2],
    pub normal: [f64; 2],
}

/// navdeck's part of the YAML.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Extras {
    pub version: String,
    /// When the map was saved, as the saver gave it (the map code reads no clock).
    pub created: String,
    /// The robot's pose when the map was saved: x, y, theta (radians).
    pub pose: Option<[f64; 3]>,
    pub landmarks: Vec<SavedLandmark>,
    pub blocks: Vec<SavedBlock>,
    pub gates: Vec<SavedGate>,
}

/// A map file's content.
#[derive(Clone, Debug, PartialEq)]
pub struct MapFile {
    pub grid: OccupancyGrid,
    pub extras: Option<Extras>,
}

/// map_server's YAML. Unknown keys are ignored, as map_server does.
#[derive(Debug, Serialize, Deserialize)]
struct MapYaml {
    image: PathBuf,
    resolution: f64,
    /// Pose of the lower-left pixel: x, y, yaw (map_server ignores yaw, and so do we).
    origin: Vec<f64>,
    #[serde(default)]
    negate: i64,
    occupied_thresh: f64,
    free_thresh: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    mode: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    navdeck: Option<Extras>,
}

/// Saved trinary pixels (map_server's map_saver): free, occupied, unknown.
const FREE_PIXEL: u8 = 254;
const OCCUPIED_PIXEL: u8 = 0;
const UNKNOWN_PIXEL: u8 = 205;

/// Reads `path` (the YAML) and the image it names.
pub fn load(path: &Path) -> Result<MapFile, MapFileError> {
    let text = crate::data::files::read_text_limited(path, crate::data::files::MAP_YAML_LIMIT)
        .map_err(|source| MapFileError::Read {
            path: path.to_path_buf(),
            error: source,
        })?;
    decode(&text, path, &mut |image_path| {
        crate::data::files::read_limited(image_path, crate::data::files::MAP_IMAGE_LIMIT).map_err(
            |source| MapFileError::Read {
                path: image_path.to_path_buf(),
                error: source,
            },
        )
    })
}

/// What the picker lists of a map: its size in metres, landmarks and when it was made,
/// from the YAML and the image's header alone (no pixels are read).
pub fn summary(path: &Path) -> Result<(f64, f64, usize, String), MapFileError> {
    let read = |p: &Path, e| MapFileError::Read {
        path: p.to_path_buf(),
        error: e,
    };
    let text = crate::data::files::read_text_limited(path, crate::data::files::MAP_YAML_LIMIT)
        .map_err(|e| read(path, e))?;
    let mut size = None;
    let map = decode(&text, path, &mut |image_path| {
        let head =
            crate::data::files::read_head(image_path, 4096).map_err(|e| read(image_path, e))?;
        let (w, h) = pgm::dimensions(&head).map_err(|source| MapFileError::Image {
            path: image_path.to_path_buf(),
            error: source,
        })?;
        size = Some((w, h));
        // A one-pixel stand-in: the summary needs no pixels.
        Ok(pgm::encode(1, 1, &[FREE_PIXEL]))
    })?;
    let (w, h) = size.unwrap_or((1, 1));
    let res = map.grid.resolution;
    let extras = map.extras.unwrap_or_default();
    Ok((
        w as f64 * res,
        h as f64 * res,
        extras.landmarks.len(),
        extras.created,
    ))
}

/// Reads a map_server YAML `text` (named `path` in errors) and the image it names, as
/// `decode` does, without turning pixels into cells.
pub fn decode_raw(
    text: &str,
    path: &Path,
    read_image: &mut dyn FnMut(&Path) -> Result<Vec<u8>, MapFileError>,
) -> Result<RawMap, MapFileError> {
    if let Some(depth) = too_deep(text) {
        return Err(MapFileError::Yaml {
            path: path.to_path_buf(),
            message: format!(
                "nested {depth} deep or more: a map YAML is flat (at most {MAX_NESTING})"
            ),
        });
    }
    let yaml: MapYaml = serde_norway::from_str(text).map_err(|e| MapFileError::Yaml {
        path: path.to_path_buf(),
        message: crate::data::number::shorten_long_numbers(&without_quoted_text(&e.to_string())),
    })?;
    let mode = check(&yaml, text, path)?;
    // map_server: the image is relative to the YAML's folder unless absolute.
    let image_path = if yaml.image.is_absolute() {
        yaml.image.clone()
    } else {
        path.parent().unwrap_or(Path::new(".")).join(&yaml.image)
    };
    let bytes = read_image(&image_path)?;
    let image = pgm::decode(&bytes).map_err(|source| MapFileError::Image {
        path: image_path.clone(),
        error: source,
    })?;
    Ok(RawMap {
        resolution: yaml.resolution,
        origin: Point2::new(yaml.origin[0], yaml.origin[1]),
        negate: yaml.negate != 0,
        occupied_thresh: yaml.occupied_thresh,
        free_thresh: yaml.free_thresh,
        mode,
        image,
        extras: yaml.navdeck,
    })
}

/// Reads a map from its YAML `text` (named `path` in errors), fetching the image it names
/// through `read_image`: the whole reader without the file system, as the fuzz target
/// drives it.
pub fn decode(
    text: &str,
    path: &Path,
    read_image: &mut dyn FnMut(&Path) -> Result<Vec<u8>, MapFileError>,
) -> Result<MapFile, MapFileError> {
    let raw = decode_raw(text, path, read_image)?;
    let grid = raw.cells(Reading::Map);
    // What the file says of itself reaches the terminal: made printable.
    let extras = raw.extras.map(|mut e| {
        e.created = crate::data::printable::printable(&e.created, Some(64));
        e
    });
    Ok(MapFile { grid, extras })
}

/// Deepest nesting a map YAML may have (it has two levels: the header and `navdeck`).
const MAX_NESTING: usize = 16;

/// How deep `text` nests, when deeper than `MAX_NESTING`: brackets and braces outside
/// quotes, and indentation (two spaces a level), counted before the parser sees them
/// (a parser's time can grow with the square of the depth).
fn too_deep(text: &str) -> Option<usize> {
    let (mut depth, mut quote) = (0usize, None);
    for c in text.chars() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), _) => {}
            (None, '"' | '\'') => quote = Some(c),
            (None, '[' | '{') => {
                depth += 1;
                if depth > MAX_NESTING {
                    return Some(depth);
                }
            }
            (None, ']' | '}') => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    let indent = text
        .lines()
        .map(|l| l.len() - l.trim_start_matches([' ', '-']).len())
        .max()
        .unwrap_or(0);
    (indent / 2 > MAX_NESTING).then_some(indent / 2)
}

/// The header's values in their bounds; `text` is the YAML, for the line of a bad field.
fn check(yaml: &MapYaml, text: &str, path: &Path) -> Result<Mode, MapFileError> {
    let field = |field: &'static str, value: String, reason| MapFileError::Field {
        path: path.to_path_buf(),
        // A header key starts its line: `resolution: 0.05`.
        line: text
            .lines()
            .position(|l| l.trim_start().starts_with(&format!("{field}:")))
            .map(|n| n + 1),
        field,
        value,
        reason,
    };
    // Bounds: a millimetre to ten metres a cell; the origin within 100 km.
    if !(0.001..=10.0).contains(&yaml.resolution) {
        return Err(field(
            "resolution",
            crate::data::number::short(yaml.resolution),
            "must lie in 0.001..=10 metres",
        ));
    }
    if yaml.origin.len() != 3 || yaml.origin.iter().any(|v| !(-1.0e5..=1.0e5).contains(v)) {
        return Err(field(
            "origin",
            format!("{:?}", yaml.origin),
            "must be [x, y, yaw], each within -100000..=100000",
        ));
    }
    for (name, value) in [
        ("occupied_thresh", yaml.occupied_thresh),
        ("free_thresh", yaml.free_thresh),
    ] {
        if !(0.0..=1.0).contains(&value) {
            return Err(field(
                name,
                crate::data::number::short(value),
                "must lie in 0..=1",
            ));
        }
    }
    if yaml.free_thresh >= yaml.occupied_thresh {
        return Err(field(
            "free_thresh",
            yaml.free_thresh.to_string(),
            "must be below occupied_thresh",
        ));
    }
    if !(yaml.negate == 0 || yaml.negate == 1) {
        return Err(field("negate", yaml.negate.to_string(), "must be 0 or 1"));
    }
    match yaml.mode.as_deref() {
        None | Some("trinary") => Ok(Mode::Trinary),
        Some("scale") => Ok(Mode::Scale),
        Some("raw") => Ok(Mode::Raw),
        Some(other) => Err(field(
            "mode",
            other.to_string(),
            "must be trinary, scale or raw",
        )),
    }
}

/// Writes `map` as `path` (the YAML) and a PGM beside it, in map_server's trinary mode.
/// Atomic: each file is written to a temporary name, synced and renamed; the previous
/// version stays as `.bak` until the new one is complete.
pub fn save(path: &Path, map: &MapFile) -> Result<(), MapFileError> {
    save_with(path, map, &mut crate::data::replace::write_synced)
}

/// `save` with more files written beside the map in the same all-or-nothing set (the
/// pose graph lidar SLAM continues from, `NAME.posegraph.json`).
pub fn save_beside(
    path: &Path,
    map: &MapFile,
    beside: Vec<(PathBuf, Vec<u8>)>,
) -> Result<(), MapFileError> {
    save_set(path, map, beside, &mut crate::data::replace::write_synced)
}

/// `save` with the byte writer passed in, so a test can fail a write half-way.
pub fn save_with(
    path: &Path,
    map: &MapFile,
    write: &mut dyn FnMut(&Path, &[u8]) -> std::io::Result<()>,
) -> Result<(), MapFileError> {
    save_set(path, map, Vec::new(), write)
}

fn save_set(
    path: &Path,
    map: &MapFile,
    beside: Vec<(PathBuf, Vec<u8>)>,
    write: &mut dyn FnMut(&Path, &[u8]) -> std::io::Result<()>,
) -> Result<(), MapFileError> {
    let image_name = path.with_extension("pgm");
    let g = &map.grid;
    let mut pixels = Vec::with_capacity(g.width * g.height);
    for row in (0..g.height).rev() {
        for col in 0..g.width {
            pixels.push(match g.get(col, row) {
                v if v < 0 => UNKNOWN_PIXEL,
                v if v >= 65 => OCCUPIED_PIXEL,
                v if v <= 19 => FREE_PIXEL,
                _ => UNKNOWN_PIXEL,
            });
        }
    }
    let yaml = MapYaml {
        image: PathBuf::from(image_name.file_name().unwrap_or_default()),
        resolution: g.resolution,
        origin: vec![g.origin.x, g.origin.y, 0.0],
        negate: 0,
        occupied_thresh: 0.65,
        free_thresh: 0.196,
        mode: Some("trinary".into()),
        navdeck: map.extras.clone(),
    };
    let text = serde_norway::to_string(&yaml).map_err(|e| MapFileError::Yaml {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    let mut files = vec![
        (image_name, pgm::encode(g.width, g.height, &pixels)),
        (path.to_path_buf(), text.into_bytes()),
    ];
    files.extend(beside);
    // All under temporary names first: a failure leaves the old pair untouched.
    crate::data::replace::replace_files(&files, write)
        .map_err(|(path, error)| MapFileError::Write { path, error })
}
