//! Zones as Nav2 costmap filter masks. Each kind is a map_server pair (`NAME.keepout.yaml`
//! and `.pgm`, `NAME.speed.yaml` and `.pgm`) and a `costmap_filter_info_server` parameter
//! file (`NAME.keepout_filter_info.yaml`, `NAME.speed_filter_info.yaml`) whose `type`,
//! `base` and `multiplier` say what a mask value means: filter value = base + multiplier
//! times the value (nav2_msgs/CostmapFilterInfo). A Nav2 user's mask of any resolution,
//! origin, negate and mode reads back into zones the same way.

use super::raster::{Frame, paint, rectangles};
use super::{Rect, SpeedLimit, Zone, ZoneError, ZoneKind, ZoneList};
use crate::map::grid::OccupancyGrid;
use crate::map::io::{MapFileError, decode_raw, io_reason};
use crate::map::pgm;
use crate::map::raw_map::{RawMap, Reading};
use std::path::{Path, PathBuf};

/// Nav2 CostmapFilterInfo `type`: keepout, speed in percent, speed in m/s.
pub const KEEPOUT_FILTER: i64 = 0;
pub const SPEED_PERCENT_FILTER: i64 = 1;
pub const SPEED_ABSOLUTE_FILTER: i64 = 2;
/// A keepout mask's lethal value (nav2_util OCC_GRID_OCCUPIED): the cost a keepout cell gets.
const KEEPOUT_VALUE: i8 = 100;

/// Which mask of a map.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MaskKind {
    Keepout,
    Speed,
}

impl MaskKind {
    pub const ALL: [MaskKind; 2] = [MaskKind::Keepout, MaskKind::Speed];

    pub fn name(self) -> &'static str {
        match self {
            MaskKind::Keepout => "keepout",
            MaskKind::Speed => "speed",
        }
    }

    fn holds(self, zone: &Zone) -> bool {
        matches!(
            (self, zone.kind),
            (MaskKind::Keepout, ZoneKind::Keepout) | (MaskKind::Speed, ZoneKind::Speed(_))
        )
    }
}

/// The files of one mask beside the map `NAME.yaml`: the mask's YAML, its image and the
/// filter info parameters.
pub fn paths(map_yaml: &Path, kind: MaskKind) -> (PathBuf, PathBuf, PathBuf) {
    let stem = map_yaml.with_extension("");
    let name = kind.name();
    let with = |suffix: String| {
        let mut s = stem.clone().into_os_string();
        s.push(suffix);
        PathBuf::from(s)
    };
    (
        with(format!(".{name}.yaml")),
        with(format!(".{name}.pgm")),
        with(format!(".{name}_filter_info.yaml")),
    )
}

/// Why a mask could not be read or written: the file, and the field or value at fault.
#[derive(Debug, thiserror::Error)]
pub enum MaskError {
    #[error("filter mask: {0}")]
    Map(#[from] MapFileError),
    #[error("cannot read filter info {path}: {reason}")]
    Read { path: PathBuf, reason: String },
    #[error("filter info {path}: {message}")]
    Yaml { path: PathBuf, message: String },
    #[error("filter info {path}: field `{field}` = {value}: {reason}")]
    Field {
        path: PathBuf,
        field: &'static str,
        value: String,
        reason: &'static str,
    },
    #[error("filter mask {path}: {error}")]
    Zone { path: PathBuf, error: ZoneError },
}

/// The files that hold `zones` of `kind` beside the map `map_yaml`, on a grid placed as
/// `frame` (the map's own, grown to cover every zone). A percent limit among m/s ones is
/// written in m/s of `max_speed`.
pub fn encode(
    zones: &ZoneList,
    kind: MaskKind,
    map_yaml: &Path,
    frame: Frame,
    max_speed: f64,
) -> Vec<(PathBuf, Vec<u8>)> {
    let (mask_yaml, mask_pgm, info) = paths(map_yaml, kind);
    let mine: Vec<&Zone> = zones.zones().iter().filter(|z| kind.holds(z)).collect();
    let frame = frame.covering(mine.iter().map(|z| &z.rect));
    let mut grid = frame.grid(0);
    let (filter, multiplier) = match kind {
        MaskKind::Keepout => {
            paint(
                &mut grid,
                mine.iter().map(|z| (z.rect, KEEPOUT_VALUE)),
                |_, v| v,
            );
            (KEEPOUT_FILTER, 1.0)
        }
        MaskKind::Speed => {
            let (filter, multiplier, values) = speed_values(&mine, max_speed);
            // Where speed zones overlap, the stricter (lower, non-zero) value holds.
            let strictest = |old: i8, new: i8| if old == 0 { new } else { old.min(new) };
            paint(&mut grid, values.into_iter(), strictest);
            (filter, multiplier)
        }
    };
    let name = |p: &Path| {
        p.file_name()
            .unwrap_or_default()
            .to_string_lossy()
            .into_owned()
    };
    let (image, mode, thresholds) = match kind {
        // Trinary as nav2_bringup's keepout masks: black is lethal, white free.
        MaskKind::Keepout => (trinary_pixels(&grid), "trinary", (0.65, 0.25)),
        // Scale over the whole range as nav2_bringup's speed masks: value = rint(occ * 100).
        MaskKind::Speed => (scale_pixels(&grid), "scale", (1.0, 0.0)),
    };
    let yaml = format!(
        "image: {}\nmode: {mode}\nresolution: {}\norigin: [{}, {}, 0.0]\nnegate: 0\n\
         occupied_thresh: {}\nfree_thresh: {}\n",
        name(&mask_pgm),
        frame.resolution,
        frame.origin.x,
        frame.origin.y,
        thresholds.0,
        thresholds.1
    );
    let topic = kind.name();
    let params = format!(
        "# Nav2 costmap filter ({topic} zones) written by navdeck: launch Nav2's\n\
         # costmap_filter_info_server and a map_server for the mask with this file.\n\
         costmap_filter_info_server:\n  ros__parameters:\n    type: {filter}\n    \
         filter_info_topic: \"/{topic}_filter_info\"\n    mask_topic: \"/{topic}_filter_mask\"\n    \
         base: 0.0\n    multiplier: {multiplier:?}\n\
         filter_mask_server:\n  ros__parameters:\n    frame_id: \"map\"\n    \
         topic_name: \"/{topic}_filter_mask\"\n    yaml_filename: \"{}\"\n",
        name(&mask_yaml)
    );
    vec![
        (mask_pgm, pgm::encode(grid.width, grid.height, &image)),
        (mask_yaml, yaml.into_bytes()),
        (info, params.into_bytes()),
    ]
}

/// The speed filter's type, multiplier and each zone's mask value (1..=100).
fn speed_values(zones: &[&Zone], max_speed: f64) -> (i64, f64, Vec<(Rect, i8)>) {
    let limits: Vec<(Rect, SpeedLimit)> = zones
        .iter()
        .filter_map(|z| match z.kind {
            ZoneKind::Speed(l) => Some((z.rect, l)),
            ZoneKind::Keepout => None,
        })
        .collect();
    let all_percent = limits
        .iter()
        .all(|(_, l)| matches!(l, SpeedLimit::Percent(_)));
    if all_percent {
        let values = limits
            .iter()
            .map(|&(r, l)| (r, mask_value(l.metres_per_second(100.0))))
            .collect();
        return (SPEED_PERCENT_FILTER, 1.0, values);
    }
    let fastest = limits
        .iter()
        .map(|(_, l)| l.metres_per_second(max_speed))
        .fold(0.0, f64::max);
    // A centimetre per second a step up to 1 m/s, else the fastest limit at 100.
    let multiplier = if fastest <= 1.0 {
        0.01
    } else {
        fastest / 100.0
    };
    let values = limits
        .iter()
        .map(|&(r, l)| (r, mask_value(l.metres_per_second(max_speed) / multiplier)))
        .collect();
    (SPEED_ABSOLUTE_FILTER, multiplier, values)
}

/// A filter value as a mask value: 1..=100 (0 would mean no limit).
fn mask_value(v: f64) -> i8 {
    v.round().clamp(1.0, 100.0) as i8
}

/// Trinary pixels (map_saver's): 0 for lethal, 254 for free, 205 for unknown; rows top down.
fn trinary_pixels(grid: &OccupancyGrid) -> Vec<u8> {
    pixels(grid, |v| match v {
        v if v < 0 => 205,
        v if v >= 65 => 0,
        _ => 254,
    })
}

/// Scale pixels (map_saver's scale mode): grey (100 - value) / 100 of white, rows top down.
fn scale_pixels(grid: &OccupancyGrid) -> Vec<u8> {
    // nav2_map_server map_io saveMapToFile, MapMode::Scale: shade = (100 - value) / 100.
    pixels(grid, |v| {
        let v = f64::from(v.clamp(0, 100));
        (255.0 * (100.0 - v) / 100.0).round() as u8
    })
}

fn pixels(grid: &OccupancyGrid, shade: impl Fn(i8) -> u8) -> Vec<u8> {
    let mut out = Vec::with_capacity(grid.width * grid.height);
    for row in (0..grid.height).rev() {
        for col in 0..grid.width {
            out.push(shade(grid.get(col, row)));
        }
    }
    out
}

/// A mask's cells as Nav2's map_server makes them: -1 unknown, 0..=100.
pub fn mask_values(raw: &RawMap) -> OccupancyGrid {
    raw.cells(Reading::FilterMask)
}

/// The parameters a filter info file gives.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FilterInfo {
    pub filter: i64,
    pub base: f64,
    pub multiplier: f64,
}

/// Zones from a mask's cells under `info`: keepout where a keepout mask is lethal, a
/// speed zone per run of cells with the same limit (Nav2 SpeedFilter: 0 and unknown are
/// no limit, and so is a limit out of bounds).
pub fn zones_from(grid: &OccupancyGrid, info: FilterInfo) -> Vec<Zone> {
    if info.filter == KEEPOUT_FILTER {
        return rectangles(grid, |v| (v == KEEPOUT_VALUE).then_some(0))
            .into_iter()
            .map(|(_, r)| Zone::keepout(r))
            .collect();
    }
    let percent = info.filter == SPEED_PERCENT_FILTER;
    let limit = |v: i8| -> Option<f64> {
        if v <= 0 {
            return None;
        }
        // Nav2 SpeedFilter: speed_limit = base + multiplier * mask value.
        let l = info.base + info.multiplier * f64::from(v);
        let ok = if percent {
            l > 0.0 && l <= 100.0
        } else {
            l > 0.0 && l <= 10.0
        };
        ok.then_some(l)
    };
    rectangles(grid, |v| limit(v).map(|_| v as u32))
        .into_iter()
        .filter_map(|(v, r)| {
            let l = limit(v as i8)?;
            let speed = if percent {
                SpeedLimit::Percent(l)
            } else {
                SpeedLimit::MetresPerSecond(l)
            };
            Some(Zone::speed(speed, r))
        })
        .collect()
}

/// Reads a Nav2 filter: its info file `info_path` and the mask it names (its
/// `yaml_filename`, else `X.yaml` beside `X_filter_info.yaml`), through `read`.
pub fn read_filter(
    info_path: &Path,
    read: &mut dyn FnMut(&Path) -> std::io::Result<Vec<u8>>,
) -> Result<ZoneList, MaskError> {
    let bytes = read(info_path).map_err(|e| MaskError::Read {
        path: info_path.to_path_buf(),
        reason: io_reason(&e),
    })?;
    let text = String::from_utf8_lossy(&bytes);
    let (info, mask_name) = parse_info(&text, info_path)?;
    let folder = info_path.parent().unwrap_or(Path::new("."));
    let mask_path = match mask_name {
        Some(name) if Path::new(&name).is_absolute() => PathBuf::from(name),
        Some(name) => folder.join(name),
        None => {
            let file = info_path.file_name().unwrap_or_default().to_string_lossy();
            match file.strip_suffix("_filter_info.yaml") {
                Some(stem) => folder.join(format!("{stem}.yaml")),
                None => {
                    return Err(MaskError::Field {
                        path: info_path.to_path_buf(),
                        field: "yaml_filename",
                        value: "(missing)".into(),
                        reason: "names no mask, and the file is not NAME_filter_info.yaml",
                    });
                }
            }
        }
    };
    let yaml = read(&mask_path).map_err(|e| MapFileError::Read {
        path: mask_path.clone(),
        error: e,
    })?;
    let yaml = String::from_utf8_lossy(&yaml);
    let raw = decode_raw(&yaml, &mask_path, &mut |p| {
        read(p).map_err(|e| MapFileError::Read {
            path: p.to_path_buf(),
            error: e,
        })
    })?;
    let zones = zones_from(&mask_values(&raw), info);
    ZoneList::new(zones).map_err(|error| MaskError::Zone {
        path: mask_path,
        error,
    })
}

/// The filter info's `type`, `base`, `multiplier` (from the node whose `ros__parameters`
/// has a `type`), and a `yaml_filename` if any node gives one.
fn parse_info(text: &str, path: &Path) -> Result<(FilterInfo, Option<String>), MaskError> {
    use serde_norway::Value;
    let yaml_err = |message: String| MaskError::Yaml {
        path: path.to_path_buf(),
        message,
    };
    let doc: Value = serde_norway::from_str(text).map_err(|e| yaml_err(e.to_string()))?;
    let Value::Mapping(nodes) = doc else {
        return Err(yaml_err(
            "not a ROS 2 parameter file: no node names at the top".into(),
        ));
    };
    let params = |node: &Value| node.get("ros__parameters").cloned();
    let mut info = None;
    let mut mask = None;
    for node in nodes.values() {
        let Some(p) = params(node) else { continue };
        if let Some(name) = p.get("yaml_filename").and_then(Value::as_str) {
            mask = Some(name.to_string());
        }
        if info.is_none() && p.get("type").is_some() {
            info = Some(p);
        }
    }
    let Some(p) = info else {
        return Err(MaskError::Field {
            path: path.to_path_buf(),
            field: "type",
            value: "(missing)".into(),
            reason: "no node's ros__parameters give the filter's type",
        });
    };
    let field = |field: &'static str, value: String, reason| MaskError::Field {
        path: path.to_path_buf(),
        field,
        value,
        reason,
    };
    let number = |name: &'static str, default: f64| -> Result<f64, MaskError> {
        match p.get(name) {
            None => Ok(default),
            Some(v) => v
                .as_f64()
                .filter(|x| x.is_finite())
                .ok_or_else(|| field(name, format!("{v:?}"), "must be a number")),
        }
    };
    let filter = p
        .get("type")
        .and_then(Value::as_i64)
        .ok_or_else(|| field("type", format!("{:?}", p.get("type")), "must be 0, 1 or 2"))?;
    if !(0..=2).contains(&filter) {
        return Err(field(
            "type",
            filter.to_string(),
            "must be 0 (keepout), 1 (speed %) or 2 (speed m/s)",
        ));
    }
    let info = FilterInfo {
        filter,
        base: number("base", 0.0)?,
        multiplier: number("multiplier", 1.0)?,
    };
    Ok((info, mask))
}

/// Reads every mask beside the map `map_yaml` that is there; none is an empty list.
pub fn load_beside(map_yaml: &Path) -> Result<ZoneList, MaskError> {
    let mut zones = ZoneList::default();
    for kind in MaskKind::ALL {
        let (_, _, info) = paths(map_yaml, kind);
        if !info.is_file() {
            continue;
        }
        let found = read_filter(&info, &mut |p| {
            crate::data::files::read_limited(p, crate::data::files::MAP_IMAGE_LIMIT)
        })?;
        zones.extend(found).map_err(|error| MaskError::Zone {
            path: info.clone(),
            error,
        })?;
    }
    Ok(zones)
}

#[cfg(test)]
#[path = "mask_tests.rs"]
mod tests;
