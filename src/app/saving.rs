//! Saving the robot's map: by key, by `:save NAME`, and every so often while exploring.

use super::App;
use super::log::Level;
use crate::map::io::{self, Extras, MapFile, SavedBlock, SavedGate, SavedLandmark};
use crate::mission::objects::Objects;
use crate::perception::markers::MarkerCategory;
use crate::pilot::Pilot;
use std::path::{Path, PathBuf};

/// The file the save key writes, and the start of the name of the one exploration keeps
/// up to date for each world (`autosave-arena`, `autosave-serial-dev-ttyusb0`).
pub const SAVE_KEY_NAME: &str = "saved";
pub const AUTOSAVE_NAME: &str = "autosave";
/// The longest place name an autosave's file name carries.
const PLACE_CHARS: usize = 40;

/// `text` as a file name's part: lower-case letters and digits, runs of anything else one
/// `-`, at most `PLACE_CHARS` long.
fn file_name_part(text: &str) -> String {
    let mut part = String::new();
    for c in text.chars().flat_map(char::to_lowercase) {
        if c.is_ascii_alphanumeric() {
            part.push(c);
        } else if !part.is_empty() && !part.ends_with('-') {
            part.push('-');
        }
    }
    let part: String = part
        .trim_end_matches('-')
        .chars()
        .take(PLACE_CHARS)
        .collect();
    part.trim_end_matches('-').to_string()
}

/// Where maps are saved, how they are dated, and when exploration last saved one.
#[derive(Default)]
pub(super) struct Files {
    pub maps_dir: Option<PathBuf>,
    date_source: Option<Box<dyn Fn() -> String + Send>>,
    last_autosave: f64,
    /// Saves asked for that did not happen: a headless run with one fails.
    pub failed: u32,
}

impl Files {
    /// No folder yet; autosaves count from session time `now`.
    pub fn new(now: f64) -> Self {
        Self {
            last_autosave: now,
            ..Self::default()
        }
    }
}

impl App {
    /// Tells the console where maps live; without a folder (headless runs and tests that
    /// do not ask) nothing is written.
    pub fn set_maps_dir(&mut self, dir: PathBuf) {
        self.files.maps_dir = Some(dir);
    }

    /// Installs the source of the date written into saved maps (the console reads no clock).
    pub fn set_date_source(&mut self, date: Box<dyn Fn() -> String + Send>) {
        self.files.date_source = Some(date);
    }

    /// Saves the map as `NAME.yaml` + `NAME.pgm` in the maps folder; logs the outcome.
    pub(super) fn save_map(&mut self, name: &str) -> bool {
        let saved = self.write_map(name);
        if !saved {
            self.files.failed += 1;
        }
        saved
    }

    /// Saves asked for this session that failed.
    pub fn failed_saves(&self) -> u32 {
        self.files.failed
    }

    fn write_map(&mut self, name: &str) -> bool {
        if name.is_empty()
            || !name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
        {
            self.log(
                Level::Error,
                format!("map not saved: name `{name}` may hold only letters, digits, - and _"),
            );
            return false;
        }
        let Some(dir) = self.files.maps_dir.clone() else {
            self.log(
                Level::Error,
                "map not saved: this session has no maps folder",
            );
            return false;
        };
        let path = dir.join(format!("{name}.yaml"));
        if let Err(e) = crate::data::replace::create_folder(&dir) {
            self.log(
                Level::Error,
                format!("map not saved: cannot create {}: {e}", dir.display()),
            );
            return false;
        }
        let created = (self.files.date_source.as_ref())
            .map_or_else(|| format!("session time {:.1} s", self.now()), |d| d());
        let block_size = self.config.mission.block_size;
        match save_map_files(&path, self.pilot(), block_size, created) {
            Ok(saved) => {
                self.log(Level::Success, saved);
                true
            }
            Err(e) => {
                self.log(Level::Error, format!("map not saved: {e}"));
                false
            }
        }
    }

    /// The name exploration autosaves under: one file per place, so that exploring one
    /// world never overwrites another's map. The twin's place is its world; a robot's is
    /// its link (the ROS 2 domain or the serial port).
    pub fn autosave_name(&self) -> String {
        let place = match self.link().ground_truth() {
            Some(truth) => truth.world().name.clone(),
            None => self.link().label(),
        };
        match file_name_part(&place) {
            part if part.is_empty() => AUTOSAVE_NAME.to_string(),
            part => format!("{AUTOSAVE_NAME}-{part}"),
        }
    }

    /// While exploring, saves `autosave-PLACE.yaml` every `[map] autosave_every` seconds;
    /// the previous one stays as its `.bak`.
    pub(super) fn autosave(&mut self, t: f64) {
        let every = self.config.map.autosave_every;
        let files = &mut self.files;
        if files.maps_dir.is_none() || every <= 0.0 || t - files.last_autosave < every {
            return;
        }
        files.last_autosave = t;
        let name = self.autosave_name();
        self.save_map(&name);
    }
}

/// Writes `pilot`'s map as the Nav2 map `path` (YAML + PGM, with the landmarks, blocks
/// and gates as navdeck's extras) and, while lidar SLAM runs, its pose graph beside it
/// (`NAME.posegraph.json`), all or none. Returns the log line naming what was written.
pub fn save_map_files(
    path: &Path,
    pilot: &Pilot,
    block_size: f64,
    created: String,
) -> Result<String, String> {
    let pose = pilot.estimated_pose();
    let landmarks: Vec<SavedLandmark> = (pilot.slam())
        .landmarks()
        .map(|l| SavedLandmark {
            id: l.id,
            category: MarkerCategory::of(l.id).label().to_string(),
            mean: [l.mean.x, l.mean.y],
            covariance: [
                [l.covariance[(0, 0)], l.covariance[(0, 1)]],
                [l.covariance[(1, 0)], l.covariance[(1, 1)]],
            ],
            sightings: l.sightings,
        })
        .collect();
    let count = landmarks.len();
    let (blocks, gates) = blocks_and_gates(pilot, block_size);
    let map = MapFile {
        grid: pilot.map_to_save(),
        extras: Some(Extras {
            version: env!("CARGO_PKG_VERSION").to_string(),
            created,
            pose: Some([pose.x, pose.y, pose.theta]),
            landmarks,
            blocks,
            gates,
        }),
    };
    let graph = pilot.lidar_slam().map(|s| {
        let file = crate::session::graph_beside(path);
        (file, s.slam.save().to_json().into_bytes())
    });
    let graph_file = graph.as_ref().map(|(file, _)| file.clone());
    let (masks, zones) = zone_masks(path, pilot, &map.grid);
    let beside = graph.into_iter().chain(masks).collect();
    io::save_beside(path, &map, beside).map_err(|e| e.to_string())?;
    let zones = match zones {
        0 => String::new(),
        n => format!(", {n} zones as Nav2 filter masks beside it"),
    };
    Ok(match (graph_file, pilot.lidar_slam()) {
        (Some(file), Some(s)) => format!(
            "map saved to {} ({count} landmarks) and its pose graph to {} ({} keyframes, {} loops)",
            path.display(),
            file.display(),
            s.slam.graph().poses.len(),
            s.slam.loops()
        ),
        _ => format!("map saved to {} ({count} landmarks){zones}", path.display()),
    })
}

/// The Nav2 filter masks of the pilot's zones beside the map `path` (keepout, speed), on
/// the map's grid grown to hold them, and how many zones they hold. A kind with no zones
/// is written (empty) only over masks already there, so a cleared zone stays cleared.
fn zone_masks(
    path: &Path,
    pilot: &Pilot,
    grid: &crate::map::grid::OccupancyGrid,
) -> (Vec<(PathBuf, Vec<u8>)>, usize) {
    use crate::map::zones::{mask, raster::Frame};
    let zones = pilot.zones();
    let max_speed = pilot.settings().robot.max_linear;
    let mut files = Vec::new();
    for kind in mask::MaskKind::ALL {
        let has = zones.zones().iter().any(|z| {
            matches!(
                (kind, z.kind),
                (
                    mask::MaskKind::Keepout,
                    crate::map::zones::ZoneKind::Keepout
                ) | (mask::MaskKind::Speed, crate::map::zones::ZoneKind::Speed(_))
            )
        });
        if has || mask::paths(path, kind).2.is_file() {
            files.extend(mask::encode(zones, kind, path, Frame::of(grid), max_speed));
        }
    }
    (files, zones.len())
}

/// Blocks and gates as the landmarks show them (seed 001's marker pairs).
fn blocks_and_gates(pilot: &Pilot, block_size: f64) -> (Vec<SavedBlock>, Vec<SavedGate>) {
    let slam = pilot.slam();
    let landmarks = slam.landmarks().map(|l| (l.id, l.mean)).collect();
    let mut objects = Objects::default();
    let here = slam.pose().position();
    let map = pilot.belief().costmap();
    objects.update(&landmarks, here, block_size, map);
    let blocks = objects
        .blocks()
        .map(|b| SavedBlock {
            colour: b.colour.label().to_string(),
            markers: b.markers,
            position: [b.position.x, b.position.y],
            confirmed: b.confirmed,
        })
        .collect();
    let gates = objects
        .gates()
        .map(|g| SavedGate {
            colour: g.colour.label().to_string(),
            markers: g.markers,
            center: [g.center.x, g.center.y],
            normal: [g.normal.0, g.normal.1],
        })
        .collect();
    (blocks, gates)
}

#[cfg(test)]
mod tests {
    use super::file_name_part;

    #[test]
    fn a_place_becomes_a_safe_file_name_part() {
        assert_eq!(file_name_part("walled garden"), "walled-garden");
        assert_eq!(
            file_name_part("serial:/dev/ttyUSB0@57600"),
            "serial-dev-ttyusb0-57600"
        );
        assert_eq!(file_name_part("../../etc/passwd"), "etc-passwd");
        assert_eq!(file_name_part("  "), "");
        assert!(file_name_part(&"x".repeat(300)).len() <= super::PLACE_CHARS);
    }
}
