//! The `:` command line as a shell has it: Up and Down recall earlier commands, Tab
//! completes command names, marker IDs and the names of maps and routes in the maps folder.

use super::App;
use super::log::Level;
use crate::keymap::{Key, KeyCode};

/// Commands kept for Up and Down.
const HISTORY: usize = 100;

/// The words Tab completes first on a line.
const COMMANDS: [&str; 15] = [
    "behaviour",
    "behaviours",
    "clear",
    "controller",
    "fault",
    "goto",
    "goto+",
    "localise",
    "mission",
    "pose",
    "quit",
    "relocalize",
    "route",
    "save",
    "waypoint",
];
const ROUTE_WORDS: [&str; 8] = [
    "clear", "load", "loop", "pause", "save", "show", "skip", "start",
];
const CONTROLLERS: [&str; 3] = ["hybrid", "pid", "pure_pursuit"];
const FAULT_WORDS: [&str; 6] = ["arm", "camera", "clear", "lidar", "odom", "slip"];

/// The line being typed, and the commands typed before.
#[derive(Default)]
pub(super) struct Prompt {
    pub line: Option<String>,
    history: Vec<String>,
    /// Which history entry Up/Down shows (an index into `history`), and the line being
    /// typed before the first Up.
    recall: Option<usize>,
    draft: String,
}

impl Prompt {
    pub fn open(&mut self, start: &str) {
        self.line = Some(start.to_string());
        self.recall = None;
    }

    /// Keeps a command for Up (not a repeat of the one before).
    fn remember(&mut self, command: &str) {
        if command.is_empty() || self.history.last().is_some_and(|h| h == command) {
            return;
        }
        self.history.push(command.to_string());
        if self.history.len() > HISTORY {
            self.history.remove(0);
        }
    }

    /// Up (`older`) or Down through the history, as a shell does.
    fn recall(&mut self, older: bool) {
        let Some(line) = self.line.as_mut() else {
            return;
        };
        let at = match (self.recall, older) {
            (None, true) if !self.history.is_empty() => {
                self.draft = line.clone();
                Some(self.history.len() - 1)
            }
            (None, _) => return,
            (Some(i), true) => Some(i.saturating_sub(1)),
            (Some(i), false) if i + 1 < self.history.len() => Some(i + 1),
            (Some(_), false) => None,
        };
        self.recall = at;
        *line = match at {
            Some(i) => self.history[i].clone(),
            None => std::mem::take(&mut self.draft),
        };
    }
}

impl App {
    /// Keys typed after `:`: enter runs the command, esc (or backspace on empty) cancels,
    /// Up and Down recall, Tab completes.
    pub(super) fn edit_prompt(&mut self, key: Key) {
        let Some(text) = self.prompt.line.as_mut() else {
            return;
        };
        match key.code {
            KeyCode::Enter => {
                let line = self.prompt.line.take().unwrap_or_default();
                match line.strip_prefix('/') {
                    // A search: only matching lines, from the newest; empty shows all.
                    Some(text) => {
                        let text = text.trim();
                        self.view.log.search = (!text.is_empty()).then(|| text.to_string());
                        self.view.log.back = 0;
                    }
                    None => {
                        self.prompt.remember(line.trim());
                        self.run_command(line.trim());
                    }
                }
            }
            KeyCode::Esc => self.prompt.line = None,
            // Backspace deletes a character; on an empty line (or a bare `/`) it closes
            // the prompt, as in vim.
            KeyCode::Backspace => {
                let search = text.starts_with('/');
                if text.pop().is_none() || (search && text.is_empty()) {
                    self.prompt.line = None;
                }
            }
            KeyCode::Up if !text.starts_with('/') => self.prompt.recall(true),
            KeyCode::Down if !text.starts_with('/') => self.prompt.recall(false),
            KeyCode::Tab if !text.starts_with('/') => self.complete(),
            KeyCode::Char(c) if !key.ctrl && !key.alt => text.push(c),
            KeyCode::Char('c') if key.ctrl => self.prompt.line = None,
            _ => {}
        }
        self.refresh_revision();
    }

    /// Tab: completes the last word as far as every candidate agrees; when several are
    /// left, the log lists them.
    fn complete(&mut self) {
        let Some(line) = self.prompt.line.clone() else {
            return;
        };
        let words: Vec<&str> = line.split_whitespace().collect();
        let partial = if line.ends_with(' ') || line.is_empty() {
            ""
        } else {
            words.last().copied().unwrap_or("")
        };
        let before: Vec<&str> = if partial.is_empty() {
            words.clone()
        } else {
            words[..words.len() - 1].to_vec()
        };
        let candidates: Vec<String> = self
            .completions(&before)
            .into_iter()
            .filter(|c| c.starts_with(partial))
            .collect();
        let Some(first) = candidates.first() else {
            return;
        };
        let common = candidates.iter().fold(first.clone(), |acc, c| {
            acc.chars()
                .zip(c.chars())
                .take_while(|(a, b)| a == b)
                .map(|(a, _)| a)
                .collect()
        });
        let stem = &line[..line.len() - partial.len()];
        let mut completed = format!("{stem}{common}");
        if candidates.len() == 1 {
            completed.push(' ');
        } else {
            self.log(Level::Info, format!("Tab: {}", candidates.join("  ")));
        }
        self.prompt.line = Some(completed);
    }

    /// What may come after `before` on a command line.
    fn completions(&self, before: &[&str]) -> Vec<String> {
        let owned = |words: &[&str]| words.iter().map(|w| w.to_string()).collect();
        match before {
            [] => owned(&COMMANDS),
            ["goto" | "goto+"] => vec!["marker".to_string()],
            ["goto" | "goto+", "marker"] => {
                let mut ids: Vec<u32> = self.pilot().slam().landmarks().map(|l| l.id).collect();
                ids.sort_unstable();
                ids.iter().map(u32::to_string).collect()
            }
            ["controller"] => owned(&CONTROLLERS),
            ["route"] => {
                // The waypoint route's words, then route mode's: tag, and the tasks.
                let mut words: Vec<String> = owned(&ROUTE_WORDS);
                if let Some(map) = self.pilot().tag_route().map() {
                    words.push("tag".into());
                    words.extend(map.tasks.keys().cloned());
                }
                words
            }
            ["route", "load" | "save"] => self.maps_named(".route.yaml"),
            ["route", "tag"] => (self.pilot().tag_route().map())
                .map(|m| m.tags.keys().map(u32::to_string).collect())
                .unwrap_or_default(),
            ["save"] => self.maps_named(".yaml"),
            ["waypoint"] => vec!["add".to_string()],
            ["mission"] => vec!["restart".to_string()],
            ["fault"] => owned(&FAULT_WORDS),
            _ => Vec::new(),
        }
    }

    /// Names in the maps folder ending in `suffix` (maps' `.yaml`, without routes'), sorted.
    fn maps_named(&self, suffix: &str) -> Vec<String> {
        let Some(dir) = &self.files.maps_dir else {
            return Vec::new();
        };
        let Ok(entries) = std::fs::read_dir(dir) else {
            return Vec::new();
        };
        let mut names: Vec<String> = entries
            .filter_map(|e| e.ok()?.file_name().into_string().ok())
            .filter(|n| suffix != ".yaml" || !n.ends_with(".route.yaml"))
            .filter_map(|n| n.strip_suffix(suffix).map(str::to_string))
            .collect();
        names.sort();
        names
    }
}
