//! The effective keymap: built-in defaults with a file laid over them, section by section.

use super::error::KeymapError;
use super::file::{self, Section};
use super::key::Key;
use crate::keymap::Action;
use crate::pilot::mode::Mode;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The shipped defaults, compiled in so navdeck runs with no files beside it.
const DEFAULT_TOML: &str = include_str!("../../keymaps/default.toml");
/// Where the defaults live in the source tree; names them in (test-only) errors.
const DEFAULT_PATH: &str = "keymaps/default.toml";

/// Key -> action for one section. `Action::Unbound` entries stay, so a mode can hide a global key.
type Table = BTreeMap<Key, Action>;

/// Which action each key asks for, per mode, with `[global]` underneath every mode.
#[derive(Clone, Debug)]
pub struct Keymap {
    global: Table,
    modes: BTreeMap<Mode, Table>,
    source: String,
}

impl Keymap {
    /// The built-in bindings: `keymaps/default.toml`, the keys of seed 001.
    pub fn default_map() -> Keymap {
        // Parsed once per process: every keymap file is laid over a copy of it.
        static BUILT_IN: std::sync::OnceLock<Keymap> = std::sync::OnceLock::new();
        BUILT_IN
            .get_or_init(|| {
                let mut map = Keymap {
                    global: Table::new(),
                    modes: BTreeMap::new(),
                    source: "built-in".to_string(),
                };
                map.overlay(DEFAULT_TOML, Path::new(DEFAULT_PATH))
                    .unwrap_or_else(|e| panic!("the built-in keymap is broken: {e}"));
                map
            })
            .clone()
    }

    /// The defaults overlaid by the keymap file at `path`.
    pub fn load(path: &Path) -> Result<Keymap, KeymapError> {
        let text = crate::data::files::read_text_limited(path, crate::data::files::TEXT_LIMIT)
            .map_err(|source| KeymapError::Read {
                path: path.to_path_buf(),
                error: source,
            })?;
        Keymap::parse_overlay(&text, path)
    }

    /// The defaults overlaid by `text`, a keymap file read from `source`.
    pub fn parse_overlay(text: &str, source: &Path) -> Result<Keymap, KeymapError> {
        let mut map = Keymap::default_map();
        map.overlay(text, source)?;
        map.source = source.display().to_string();
        // Quitting stops the robot: every mode keeps a way out.
        for mode in Mode::ALL {
            if !map.bindings(mode).iter().any(|(a, _)| *a == Action::Quit) {
                return Err(KeymapError::NoQuit {
                    path: source.to_path_buf(),
                    mode: mode.label().to_lowercase(),
                });
            }
        }
        Ok(map)
    }

    /// Each binding of the file replaces that key's binding in the same section.
    fn overlay(&mut self, text: &str, path: &Path) -> Result<(), KeymapError> {
        for section in file::parse(text, path)? {
            let table = match section.section {
                Section::Global => &mut self.global,
                Section::Mode(mode) => self.modes.entry(mode).or_default(),
            };
            table.extend(section.bindings);
        }
        Ok(())
    }

    /// What `key` does in `mode`: the mode's own binding, else the global one.
    /// A key bound to "none" does nothing (in a mode section it also hides the global binding).
    pub fn lookup(&self, mode: Mode, key: Key) -> Option<Action> {
        let action = self
            .modes
            .get(&mode)
            .and_then(|table| table.get(&key))
            .or_else(|| self.global.get(&key))?;
        Some(*action).filter(|a| *a != Action::Unbound)
    }

    /// For the help overlay: every action that some key reaches in `mode`, with all its keys,
    /// in `Action::ALL` order; plain keys come before ones with ctrl or alt.
    pub fn bindings(&self, mode: Mode) -> Vec<(Action, Vec<Key>)> {
        let mode_keys = self.modes.get(&mode).into_iter().flat_map(|t| t.keys());
        let keys: BTreeSet<Key> = self.global.keys().chain(mode_keys).copied().collect();
        let mut by_action: BTreeMap<Action, Vec<Key>> = BTreeMap::new();
        for key in keys {
            if let Some(action) = self.lookup(mode, key) {
                by_action.entry(action).or_default().push(key);
            }
        }
        Action::ALL
            .into_iter()
            .filter_map(|action| {
                let mut keys = by_action.remove(&action)?;
                keys.sort_by_key(|k| (k.ctrl || k.alt, *k));
                Some((action, keys))
            })
            .collect()
    }

    /// "built-in", or the path of the file laid over the defaults, as it was given.
    pub fn source(&self) -> &str {
        &self.source
    }
}

impl Default for Keymap {
    fn default() -> Keymap {
        Keymap::default_map()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn overlay(text: &str) -> Keymap {
        Keymap::parse_overlay(text, Path::new("user.toml")).unwrap()
    }

    fn key(name: &str) -> Key {
        name.parse().unwrap()
    }

    #[test]
    fn a_file_binding_replaces_the_default_for_that_key_only() {
        let map = overlay("[manual]\nw = \"backward\"\n");
        assert_eq!(map.lookup(Mode::Manual, key("w")), Some(Action::Backward));
        assert_eq!(map.lookup(Mode::Manual, key("s")), Some(Action::Backward));
        assert_eq!(map.lookup(Mode::Manual, key("a")), Some(Action::TurnLeft));
        assert_eq!(map.source(), "user.toml");
        assert_eq!(Keymap::default_map().source(), "built-in");
    }

    #[test]
    fn none_in_global_unbinds_everywhere_the_mode_does_not_rebind() {
        let map = overlay("[global]\nq = \"none\"\n");
        // The map picker binds q itself (it leaves the picker).
        for mode in Mode::ALL.into_iter().filter(|m| *m != Mode::Load) {
            assert_eq!(map.lookup(mode, key("q")), None, "{mode:?}");
        }
        assert_eq!(map.lookup(Mode::Load, key("q")), Some(Action::ModeManual));
        assert_eq!(map.lookup(Mode::Race, key("ctrl-c")), Some(Action::Quit));
    }

    #[test]
    fn none_in_a_mode_hides_the_global_binding_in_that_mode_only() {
        let map = overlay("[manual]\nq = \"none\"\n");
        assert_eq!(map.lookup(Mode::Manual, key("q")), None);
        assert_eq!(map.lookup(Mode::Exploration, key("q")), Some(Action::Quit));
        let quit_keys = map
            .bindings(Mode::Manual)
            .into_iter()
            .find(|(a, _)| *a == Action::Quit)
            .map(|(_, keys)| keys);
        assert_eq!(quit_keys, Some(vec![key("ctrl-c")]));
    }

    #[test]
    fn a_mode_binding_wins_over_a_global_one() {
        let map = overlay("[global]\nx = \"help\"\n[race]\nx = \"stop\"\n");
        assert_eq!(map.lookup(Mode::Race, key("x")), Some(Action::Stop));
        assert_eq!(map.lookup(Mode::Load, key("x")), Some(Action::Help));
    }

    #[test]
    fn unbound_never_appears_in_bindings() {
        let map = overlay("[global]\nz = \"none\"\n");
        for mode in Mode::ALL {
            assert!(
                map.bindings(mode)
                    .iter()
                    .all(|(a, _)| *a != Action::Unbound)
            );
        }
    }

    #[test]
    fn bindings_follow_action_order_with_plain_keys_first() {
        let bindings = Keymap::default_map().bindings(Mode::Exploration);
        let order: Vec<usize> = bindings
            .iter()
            .map(|(a, _)| Action::ALL.iter().position(|x| x == a).unwrap())
            .collect();
        assert!(order.is_sorted(), "{order:?}");
        let quit = bindings.iter().find(|(a, _)| *a == Action::Quit).unwrap();
        assert_eq!(quit.1, vec![key("q"), key("ctrl-c")]);
    }
}
