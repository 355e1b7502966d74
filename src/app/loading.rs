//! Load mode (`l`, seed 001): pick a saved map from the maps folder; its landmarks become
//! the filter's prior and its grid joins the planning map.

use super::App;
use super::log::Level;
use crate::map::io;
use crate::pilot::{self, mode::Mode};
use std::path::PathBuf;

/// One map file in the picker.
#[derive(Clone, Debug, PartialEq)]
pub struct MapEntry {
    pub name: String,
    pub path: PathBuf,
    /// Size in metres and landmarks, or why the file cannot be read.
    pub summary: Result<(f64, f64, usize, String), String>,
}

/// The picker's state.
#[derive(Clone, Debug, Default)]
pub(super) struct Picker {
    pub entries: Vec<MapEntry>,
    pub selected: usize,
}

impl App {
    /// Lists the maps folder's map files, newest name order, for the picker.
    pub(super) fn open_picker(&mut self) {
        let Some(dir) = self.files.maps_dir.clone() else {
            self.picker = Picker::default();
            self.log(Level::Warn, "no maps folder in this session (--maps-dir)");
            return;
        };
        let mut entries: Vec<MapEntry> = std::fs::read_dir(&dir)
            .map(|rd| {
                rd.filter_map(Result::ok)
                    .map(|e| e.path())
                    .filter(|p| p.extension().is_some_and(|x| x == "yaml"))
                    .map(|path| {
                        let name = path
                            .file_stem()
                            .map_or(String::new(), |s| s.to_string_lossy().into_owned());
                        let summary = io::load(&path)
                            .map(|m| {
                                let (w, h) = m.grid.extent();
                                let extras = m.extras.unwrap_or_default();
                                (w, h, extras.landmarks.len(), extras.created)
                            })
                            .map_err(|e| e.to_string());
                        MapEntry {
                            name,
                            path,
                            summary,
                        }
                    })
                    .collect()
            })
            .unwrap_or_default();
        entries.sort_by(|a, b| a.name.cmp(&b.name));
        let count = entries.len();
        self.picker = Picker {
            entries,
            selected: 0,
        };
        self.log(
            Level::Info,
            format!(
                "load: {count} maps in {}; up/down choose, enter loads, m leaves",
                dir.display()
            ),
        );
    }

    pub(super) fn pick(&mut self, step: isize) {
        let n = self.picker.entries.len();
        if n > 0 {
            self.picker.selected =
                (self.picker.selected as isize + step).rem_euclid(n as isize) as usize;
        }
    }

    /// Loads the chosen map; a file that cannot be read leaves the current map as it is.
    pub(super) fn load_selected(&mut self) {
        let Some(entry) = self.picker.entries.get(self.picker.selected).cloned() else {
            self.log(Level::Warn, "no map to load");
            return;
        };
        let map = match io::load(&entry.path) {
            Ok(map) => map,
            Err(e) => {
                self.log(
                    Level::Error,
                    format!("map not loaded, the current one stays: {e}"),
                );
                return;
            }
        };
        self.run_intent(pilot::Intent::AdoptMap {
            map: Box::new(map),
            source: entry.path.display().to_string(),
        });
    }

    /// The picker's maps and the chosen one, in load mode.
    pub fn map_picker(&self) -> Option<(&[MapEntry], usize)> {
        (self.pilot.mode() == Mode::Load)
            .then_some((self.picker.entries.as_slice(), self.picker.selected))
    }
}
