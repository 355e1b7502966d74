//! Load mode (`l`, seed 001): pick a saved map from the maps folder; its landmarks become
//! the filter's prior and its grid joins the planning map.

use super::App;
use super::log::Level;
use crate::map::agreement::mismatches;
use crate::map::io::{self, MapFile};
use crate::pilot::{self, mode::Mode};
use std::path::{Path, PathBuf};
use std::sync::mpsc::{Receiver, RecvTimeoutError, TryRecvError, channel};

/// One map file in the picker.
#[derive(Clone, Debug, PartialEq)]
pub struct MapEntry {
    pub name: String,
    pub path: PathBuf,
    /// Size in metres and landmarks, or why the file cannot be read.
    pub summary: Result<(f64, f64, usize, String), String>,
}

/// The picker's state. The folder is listed on a worker thread (a slow disk or a hostile
/// file never stalls the console); its list arrives through `pending`.
#[derive(Debug, Default)]
pub(super) struct Picker {
    pub entries: Vec<MapEntry>,
    pub selected: usize,
    pending: Option<(PathBuf, Receiver<Vec<MapEntry>>)>,
    /// A map that does not fit the robot's, read and waiting for a second enter.
    confirming: Option<(usize, Box<MapFile>)>,
}

/// How long a key that needs the list waits for it, seconds.
const LIST_WAIT: f64 = 1.0;

/// The maps folder's map files in name order, each summed up from its header.
fn list_maps(dir: &Path) -> Vec<MapEntry> {
    let mut entries: Vec<MapEntry> = std::fs::read_dir(dir)
        .map(|rd| {
            rd.filter_map(Result::ok)
                .map(|e| e.path())
                .filter(|p| p.extension().is_some_and(|x| x == "yaml"))
                .map(|path| MapEntry {
                    name: path
                        .file_stem()
                        .map_or(String::new(), |s| s.to_string_lossy().into_owned()),
                    summary: io::summary(&path).map_err(|e| e.to_string()),
                    path,
                })
                .collect()
        })
        .unwrap_or_default();
    entries.sort_by(|a, b| a.name.cmp(&b.name));
    entries
}

impl App {
    /// Starts listing the maps folder for the picker.
    pub(super) fn open_picker(&mut self) {
        let Some(dir) = self.files.maps_dir.clone() else {
            self.picker = Picker::default();
            self.log(Level::Warn, "no maps folder in this session (--maps-dir)");
            return;
        };
        let (send, receive) = channel();
        let listed = dir.clone();
        let spawned = std::thread::Builder::new()
            .name("navdeck-maps".into())
            .spawn(move || {
                let _ = send.send(list_maps(&listed));
            });
        if let Err(e) = spawned {
            self.log(
                Level::Error,
                format!("load: cannot list {}: {e}", dir.display()),
            );
            return;
        }
        self.picker = Picker {
            pending: Some((dir, receive)),
            ..Picker::default()
        };
    }

    /// Takes the list once it has arrived; with `wait`, waits up to `LIST_WAIT` for it
    /// (a key that needs the list).
    pub(super) fn poll_picker(&mut self, wait: bool) {
        let Some((dir, receive)) = &self.picker.pending else {
            return;
        };
        let got = if wait {
            receive.recv_timeout(std::time::Duration::from_secs_f64(LIST_WAIT))
        } else {
            receive.try_recv().map_err(|e| match e {
                TryRecvError::Empty => RecvTimeoutError::Timeout,
                TryRecvError::Disconnected => RecvTimeoutError::Disconnected,
            })
        };
        let dir = dir.clone();
        match got {
            Ok(entries) => {
                let count = entries.len();
                self.picker = Picker {
                    entries,
                    ..Picker::default()
                };
                self.log(
                    Level::Info,
                    format!(
                        "load: {count} maps in {}; up/down choose, enter loads, m leaves",
                        dir.display()
                    ),
                );
            }
            Err(RecvTimeoutError::Timeout) if wait => {
                self.log(
                    Level::Warn,
                    format!("load: still listing {}", dir.display()),
                );
            }
            Err(RecvTimeoutError::Timeout) => {}
            Err(RecvTimeoutError::Disconnected) => {
                self.picker.pending = None;
                self.log(
                    Level::Error,
                    format!("load: listing {} failed", dir.display()),
                );
            }
        }
    }

    pub(super) fn pick(&mut self, step: isize) {
        self.poll_picker(true);
        let n = self.picker.entries.len();
        if n > 0 {
            self.picker.selected =
                (self.picker.selected as isize + step).rem_euclid(n as isize) as usize;
        }
        self.picker.confirming = None;
    }

    /// Loads the chosen map; a file that cannot be read leaves the current map as it is,
    /// and one that disagrees with what the robot has sensed waits for a second enter.
    pub(super) fn load_selected(&mut self) {
        self.poll_picker(true);
        let selected = self.picker.selected;
        let Some(entry) = self.picker.entries.get(selected).cloned() else {
            self.log(Level::Warn, "no map to load");
            return;
        };
        let (map, asked) = match self.picker.confirming.take() {
            Some((index, map)) if index == selected => (map, true),
            _ => match io::load(&entry.path) {
                Ok(map) => (Box::new(map), false),
                Err(e) => {
                    self.log(
                        Level::Error,
                        format!("map not loaded, the current one stays: {e}"),
                    );
                    return;
                }
            },
        };
        if !asked && !self.fits(&entry, &map) {
            self.picker.confirming = Some((selected, map));
            return;
        }
        self.run_intent(pilot::Intent::AdoptMap {
            map,
            source: entry.path.display().to_string(),
        });
        self.load_zones_beside(&entry.path);
    }

    /// Whether `map` may be loaded at once: true when nothing speaks against it, else it
    /// says why in the log and asks for enter again.
    fn fits(&mut self, entry: &MapEntry, map: &MapFile) -> bool {
        let pilot = self.pilot();
        let own = pilot.belief().sensed_grid();
        let found = mismatches(&map.grid, &own, pilot.estimated_pose().position());
        if found.is_empty() {
            return true;
        }
        let why: Vec<String> = found.iter().map(ToString::to_string).collect();
        self.log(
            Level::Warn,
            format!(
                "{} does not fit this robot's map: {}. Enter again loads it anyway (u undoes a load), esc keeps the current map",
                entry.name,
                why.join("; ")
            ),
        );
        false
    }

    /// Whether the chosen map waits for a second enter.
    pub fn picker_confirming(&self) -> bool {
        self.picker
            .confirming
            .as_ref()
            .is_some_and(|(index, _)| *index == self.picker.selected)
    }

    /// Whether the picker's list is still being made.
    pub fn picker_listing(&self) -> bool {
        self.picker.pending.is_some()
    }

    /// The picker's maps and the chosen one, in load mode.
    pub fn map_picker(&self) -> Option<(&[MapEntry], usize)> {
        (self.pilot().mode() == Mode::Load)
            .then_some((self.picker.entries.as_slice(), self.picker.selected))
    }
}
