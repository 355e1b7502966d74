//! Reading one keymap file: TOML sections of `key = "action"`, checked line by line.

use super::error::KeymapError;
use super::key::Key;
use crate::keymap::Action;
use crate::pilot::mode::Mode;
use std::collections::HashMap;
use std::path::Path;
use toml::de::{DeTable, DeValue};

/// A table of a keymap file: `[global]` or one mode's.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Section {
    Global,
    Mode(Mode),
}

impl Section {
    fn from_name(name: &str) -> Option<Section> {
        if name == "global" {
            Some(Section::Global)
        } else {
            Mode::from_section(name).map(Section::Mode)
        }
    }
}

/// The bindings one section of a file sets, in file order.
#[derive(Debug)]
pub(super) struct SectionBindings {
    pub section: Section,
    pub bindings: Vec<(Key, Action)>,
}

/// Parses a keymap file's text; `path` only names the file in errors.
pub(super) fn parse(text: &str, path: &Path) -> Result<Vec<SectionBindings>, KeymapError> {
    let doc = DeTable::parse(text).map_err(|e| toml_error(text, path, &e))?;
    let at = |offset: usize| line_of(text, offset);
    let mut sections = Vec::new();
    for (name, value) in in_file_order(doc.get_ref()) {
        let line = at(name.span().start);
        let Some(table) = value.get_ref().as_table() else {
            return Err(KeymapError::OutsideSection {
                path: path.to_path_buf(),
                line,
                name: name.get_ref().to_string(),
            });
        };
        let section_name = name.get_ref().as_ref();
        let Some(section) = Section::from_name(section_name) else {
            return Err(KeymapError::UnknownSection {
                path: path.to_path_buf(),
                line,
                section: section_name.to_string(),
            });
        };
        let mut bindings = Vec::new();
        // Normalised key -> (name as written, line), to catch two spellings of one key.
        let mut seen: HashMap<Key, (&str, usize)> = HashMap::new();
        for (key_name, value) in in_file_order(table) {
            let key_name_str: &str = key_name.get_ref();
            let line = at(key_name.span().start);
            let value_line = at(value.span().start);
            let Some(action_name) = value.get_ref().as_str() else {
                return Err(KeymapError::NotAString {
                    path: path.to_path_buf(),
                    line: value_line,
                    section: section_name.to_string(),
                    key: key_name_str.to_string(),
                    found: value.get_ref().type_str(),
                });
            };
            let key: Key = key_name_str.parse().map_err(|reason| KeymapError::BadKey {
                path: path.to_path_buf(),
                line,
                section: section_name.to_string(),
                reason,
            })?;
            let Some(action) = Action::from_name(action_name) else {
                return Err(KeymapError::UnknownAction {
                    path: path.to_path_buf(),
                    line: value_line,
                    section: section_name.to_string(),
                    key: key_name_str.to_string(),
                    action: action_name.to_string(),
                });
            };
            if let Some((first_key, first_line)) = seen.insert(key, (key_name_str, line)) {
                return Err(KeymapError::Duplicate {
                    path: path.to_path_buf(),
                    line,
                    section: section_name.to_string(),
                    key: key_name_str.to_string(),
                    first_key: first_key.to_string(),
                    first_line,
                });
            }
            bindings.push((key, action));
        }
        sections.push(SectionBindings { section, bindings });
    }
    Ok(sections)
}

type Entry<'t, 'i> = (
    &'t toml::Spanned<toml::de::DeString<'i>>,
    &'t toml::Spanned<DeValue<'i>>,
);

/// A table's entries sorted by where their keys stand in the file, so the first error reported
/// is the first one a reader meets.
fn in_file_order<'t, 'i>(table: &'t DeTable<'i>) -> Vec<Entry<'t, 'i>> {
    let mut entries: Vec<_> = table.iter().collect();
    entries.sort_by_key(|(key, _)| key.span().start);
    entries
}

/// 1-based line of a byte offset (clamped to the text, so it cannot panic).
fn line_of(text: &str, offset: usize) -> usize {
    let end = offset.min(text.len());
    text.as_bytes()[..end]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

/// TOML's own complaint, placed on its line, with a hint for the mistakes keymap writers make.
fn toml_error(text: &str, path: &Path, error: &toml::de::Error) -> KeymapError {
    let span = error.span().unwrap_or(0..0);
    let mut message = error.message().to_string();
    let snippet = text.get(span.clone()).unwrap_or("").trim();
    if !snippet.is_empty() && !snippet.contains('\n') {
        message.push_str(&format!(" at \"{snippet}\""));
    }
    if message.starts_with("duplicate key") {
        message.push_str(" (a key may appear once per section, and a section once per file)");
    } else if message.contains("unquoted key") {
        message.push_str(
            " (key names other than letters, digits, '-' and '_' need quotes: \"?\" = \"help\")",
        );
    } else if message.starts_with("invalid boolean") {
        message.push_str(" (action names need quotes: w = \"forward\")");
    }
    KeymapError::Toml {
        path: path.to_path_buf(),
        line: line_of(text, span.start),
        message,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn error(text: &str) -> String {
        parse(text, Path::new("keymaps/bad.toml"))
            .expect_err("should be refused")
            .to_string()
    }

    fn assert_mentions(message: &str, parts: &[&str]) {
        for part in parts {
            assert!(message.contains(part), "{part:?} missing from: {message}");
        }
    }

    #[test]
    fn reads_sections_in_file_order_with_normalised_keys() {
        let text =
            "[manual]\nw = \"forward\"\nshift-s = 'backward'\n\n[global]\n\"?\" = \"help\"\n";
        let sections = parse(text, Path::new("ok.toml")).unwrap();
        assert_eq!(sections.len(), 2);
        assert_eq!(sections[0].section, Section::Mode(Mode::Manual));
        assert_eq!(
            sections[0].bindings,
            vec![
                (Key::char('w'), Action::Forward),
                (Key::char('S'), Action::Backward)
            ]
        );
        assert_eq!(sections[1].section, Section::Global);
        assert_eq!(sections[1].bindings, vec![(Key::char('?'), Action::Help)]);
    }

    #[test]
    fn an_empty_file_changes_nothing() {
        assert!(
            parse("# nothing here\n", Path::new("empty.toml"))
                .unwrap()
                .is_empty()
        );
    }

    #[test]
    fn unknown_key_name_names_file_line_key_and_section() {
        let message =
            error("[global]\nq = \"quit\"\n\n[manual]\nw = \"forward\"\nbogus = \"stop\"\n");
        assert_mentions(&message, &["keymaps/bad.toml:6:", "\"bogus\"", "[manual]"]);
    }

    #[test]
    fn unknown_action_names_file_line_action_key_and_section() {
        let message = error("[manual]\nw = \"forward\"\nx = \"fly\"\n");
        assert_eq!(
            message,
            "keymaps/bad.toml:3: unknown action \"fly\" for key \"x\" in [manual]"
        );
    }

    #[test]
    fn unknown_section_names_file_line_and_section() {
        let message = error("[global]\nq = \"quit\"\n[manul]\nw = \"forward\"\n");
        assert_mentions(&message, &["keymaps/bad.toml:3:", "[manul]"]);
    }

    #[test]
    fn binding_outside_a_section_is_refused_with_its_line() {
        let message = error("# a comment\nw = \"forward\"\n");
        assert_mentions(
            &message,
            &["keymaps/bad.toml:2:", "\"w\"", "outside any section"],
        );
    }

    #[test]
    fn two_spellings_of_one_key_name_both_lines() {
        // (file, line of the second spelling, second spelling, first spelling and its line)
        let cases = [
            (
                "[global]\nspace = \"help\"\n\" \" = \"quit\"\n",
                3,
                "\" \"",
                "\"space\" on line 2",
            ),
            (
                "[manual]\nW = \"forward\"\n\n\nshift-w = \"stop\"\n",
                5,
                "\"shift-w\"",
                "\"W\" on line 2",
            ),
            (
                "[global]\n\"C-c\" = \"quit\"\nctrl-c = \"quit\"\n",
                3,
                "\"ctrl-c\"",
                "\"C-c\" on line 2",
            ),
        ];
        for (text, line, second, first) in cases {
            let message = error(text);
            let location = format!("keymaps/bad.toml:{line}:");
            assert_mentions(&message, &[&location, second, first]);
        }
    }

    #[test]
    fn the_same_key_in_two_sections_is_no_duplicate() {
        let text = "[global]\nc = \"gripper_close\"\n[manual]\nc = \"stop\"\n";
        assert!(parse(text, Path::new("ok.toml")).is_ok());
    }

    #[test]
    fn a_key_written_twice_is_a_keymap_error_with_its_line() {
        let message = error("[manual]\nw = \"forward\"\ns = \"backward\"\nw = \"stop\"\n");
        assert_mentions(&message, &["keymaps/bad.toml:4:", "duplicate key", "\"w\""]);
        let message = error("[manual]\nw = \"forward\"\n[global]\n[manual]\n");
        assert_mentions(&message, &["keymaps/bad.toml:4:", "manual"]);
    }

    #[test]
    fn a_value_that_is_not_a_string_is_refused_with_its_line() {
        let message = error("[manual]\nw = \"forward\"\ns = 3\n");
        assert_mentions(&message, &["keymaps/bad.toml:3:", "\"s\"", "integer"]);
        let message = error("[manual]\n\n[manual.extra]\nq = \"quit\"\n");
        assert_mentions(&message, &["keymaps/bad.toml:3:", "\"extra\"", "table"]);
    }

    #[test]
    fn toml_mistakes_get_a_line_and_a_hint() {
        let message = error("[global]\nq = \"quit\"\n? = \"help\"\n");
        assert_mentions(&message, &["keymaps/bad.toml:3:", "need quotes"]);
        let message = error("[manual]\n\nw = forward\n");
        assert_mentions(&message, &["keymaps/bad.toml:3:", "w = \"forward\""]);
    }

    #[test]
    fn line_of_counts_from_one_and_never_panics() {
        assert_eq!(line_of("a\nb\nc", 0), 1);
        assert_eq!(line_of("a\nb\nc", 2), 2);
        assert_eq!(line_of("a\nb\nc", 99), 3);
    }
}
