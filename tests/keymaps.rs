//! The shipped keymap files, read the way a user's `--keymap` is read.

use navdeck::app::mode::Mode;
use navdeck::keymap::Action;
use navdeck::keymap::{Key, Keymap, KeymapError};
use std::path::{Path, PathBuf};

fn keymaps_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("keymaps")
}

fn key(name: &str) -> Key {
    name.parse().unwrap_or_else(|e| panic!("{name:?}: {e}"))
}

fn shipped(name: &str) -> Keymap {
    let path = keymaps_dir().join(name);
    Keymap::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

fn keys_for(map: &Keymap, mode: Mode, action: Action) -> Vec<Key> {
    map.bindings(mode)
        .into_iter()
        .find(|(a, _)| *a == action)
        .map(|(_, keys)| keys)
        .unwrap_or_default()
}

#[test]
fn every_shipped_keymap_loads() {
    let mut loaded = Vec::new();
    for entry in std::fs::read_dir(keymaps_dir()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let map = Keymap::load(&path).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(map.source(), path.display().to_string());
            loaded.push(path);
        }
    }
    assert!(loaded.len() >= 2, "found only {loaded:?}");
}

#[test]
fn built_in_defaults_are_default_toml() {
    let built_in = Keymap::default_map();
    let file = shipped("default.toml");
    for mode in Mode::ALL {
        assert_eq!(built_in.bindings(mode), file.bindings(mode), "{mode:?}");
    }
}

#[test]
fn defaults_have_the_seed_keys() {
    let map = Keymap::default_map();
    let global = [
        ("m", Action::ModeManual),
        ("e", Action::ModeExplore),
        ("t", Action::ModeThink),
        ("p", Action::ModeFollow),
        ("r", Action::ModeRace),
        ("l", Action::ModeLoad),
        ("o", Action::GripperOpen),
        ("q", Action::Quit),
        ("ctrl-c", Action::Quit),
        ("space", Action::EmergencyStop),
        ("?", Action::Help),
        ("0", Action::CenterView),
        ("up", Action::PanUp),
    ];
    for mode in Mode::ALL {
        for (name, action) in global {
            if mode == Mode::Load && name == "up" {
                // The map picker chooses with the arrows.
                assert_eq!(map.lookup(mode, key(name)), Some(Action::CursorUp));
                continue;
            }
            if mode == Mode::Route && name == "up" {
                // Route mode chooses a task or a tag with the arrows.
                assert_eq!(map.lookup(mode, key(name)), Some(Action::CursorUp));
                continue;
            }
            if mode == Mode::Load && name == "q" {
                // q leaves the map picker rather than the console (ctrl-c still quits).
                assert_eq!(map.lookup(mode, key(name)), Some(Action::ModeManual));
                continue;
            }
            if mode == Mode::Gripper && matches!(name, "r" | "f") {
                // In gripper mode r and f move the arm's tool up and down.
                let arm = if name == "r" {
                    Action::ArmUp
                } else {
                    Action::ArmDown
                };
                assert_eq!(map.lookup(mode, key(name)), Some(arm));
                continue;
            }
            if mode == Mode::Thinking && matches!(name, "l" | "up") {
                // Thinking mode's goal cursor moves with h j k l and the arrows.
                assert_eq!(
                    map.lookup(mode, key(name)),
                    Some(if name == "l" {
                        Action::CursorRight
                    } else {
                        Action::CursorUp
                    })
                );
                continue;
            }
            assert_eq!(
                map.lookup(mode, key(name)),
                Some(action),
                "{name} in {mode:?}"
            );
        }
    }
    let manual = [
        ("w", Action::Forward),
        ("s", Action::Backward),
        ("a", Action::TurnLeft),
        ("d", Action::TurnRight),
        ("]", Action::SpeedUp),
        ("[", Action::SpeedDown),
    ];
    for (name, action) in manual {
        assert_eq!(map.lookup(Mode::Manual, key(name)), Some(action), "{name}");
        assert_eq!(map.lookup(Mode::Exploration, key(name)), None, "{name}");
    }
    // One stop key in every mode.
    for mode in Mode::ALL.into_iter().filter(|m| *m != Mode::Load) {
        assert_eq!(map.lookup(mode, key("x")), Some(Action::Stop), "{mode:?}");
    }
    assert_eq!(map.lookup(Mode::Manual, key("L")), Some(Action::ToggleScan));
    assert_eq!(
        map.lookup(Mode::Manual, key("T")),
        Some(Action::ToggleTrail)
    );
}

#[test]
fn c_stops_in_manual_but_closes_the_gripper_elsewhere() {
    let map = Keymap::default_map();
    assert_eq!(map.lookup(Mode::Manual, key("c")), Some(Action::Stop));
    assert_eq!(
        map.lookup(Mode::Exploration, key("c")),
        Some(Action::GripperClose)
    );
}

#[test]
fn help_lists_what_each_mode_really_does() {
    let map = Keymap::default_map();
    assert_eq!(
        keys_for(&map, Mode::Manual, Action::Forward),
        vec![key("w")]
    );
    assert!(keys_for(&map, Mode::Manual, Action::GripperClose).is_empty());
    assert!(keys_for(&map, Mode::Manual, Action::Stop).contains(&key("c")));
    assert_eq!(
        keys_for(&map, Mode::Exploration, Action::GripperClose),
        vec![key("c")]
    );
    assert!(keys_for(&map, Mode::Exploration, Action::Forward).is_empty());
    assert_eq!(
        keys_for(&map, Mode::Manual, Action::ZoomIn),
        vec![key("+"), key("=")]
    );
}

#[test]
fn teleop_layout_drives_with_ijkl_and_changes_speeds_with_q_z_w_x_e_c() {
    let map = shipped("teleop_twist_keyboard.toml");
    let manual = [
        ("u", Action::ForwardLeft),
        ("i", Action::Forward),
        ("o", Action::ForwardRight),
        ("j", Action::TurnLeft),
        ("k", Action::Stop),
        ("l", Action::TurnRight),
        ("m", Action::BackwardLeft),
        (",", Action::Backward),
        (".", Action::BackwardRight),
        ("q", Action::SpeedUp),
        ("z", Action::SpeedDown),
        ("w", Action::LinearUp),
        ("x", Action::LinearDown),
        ("e", Action::AngularUp),
        ("c", Action::AngularDown),
        ("E", Action::ModeExplore),
        ("O", Action::GripperOpen),
        ("C", Action::GripperClose),
        ("L", Action::ModeLoad),
    ];
    for (name, action) in manual {
        assert_eq!(map.lookup(Mode::Manual, key(name)), Some(action), "{name}");
    }
    assert_eq!(map.lookup(Mode::Manual, key("s")), None);
    // q raises the speeds in every mode, so it never quits; ctrl-c still does.
    assert_eq!(
        map.lookup(Mode::Exploration, key("q")),
        Some(Action::SpeedUp)
    );
    assert_eq!(map.lookup(Mode::Manual, key("ctrl-c")), Some(Action::Quit));
    assert_eq!(
        map.lookup(Mode::Exploration, key("o")),
        Some(Action::GripperOpen)
    );
    // i drives forward in manual mode only; elsewhere it is route mode, as by default,
    // and I reaches route mode from manual mode.
    assert_eq!(
        map.lookup(Mode::Exploration, key("i")),
        Some(Action::ModeRoute)
    );
    assert_eq!(map.lookup(Mode::Manual, key("I")), Some(Action::ModeRoute));
}

#[test]
fn default_toml_documents_every_action() {
    let text = std::fs::read_to_string(keymaps_dir().join("default.toml")).unwrap();
    for action in Action::ALL {
        assert!(
            text.contains(action.name()),
            "{} is not documented",
            action.name()
        );
    }
}

/// Writes `text` to a file named bad.toml in a fresh directory and loads it.
fn load_bad(test: &str, text: &str) -> String {
    let dir = std::env::temp_dir().join(format!("navdeck-keymap-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bad.toml");
    std::fs::write(&path, text).unwrap();
    let result = Keymap::load(&path);
    std::fs::remove_dir_all(&dir).unwrap();
    result.expect_err("should be refused").to_string()
}

#[test]
fn each_mistake_names_the_file_and_line() {
    let cases = [
        (
            "key_name",
            "[manual]\nw = \"forward\"\nctrl-bogus = \"stop\"\n",
            3,
            "\"ctrl-bogus\"",
        ),
        ("action", "[global]\n\n\n\ng = \"fly\"\n", 5, "\"fly\""),
        (
            "section",
            "[global]\nq = \"quit\"\n[driving]\n",
            3,
            "[driving]",
        ),
        (
            "duplicate",
            "[race]\nspace = \"stop\"\nx = \"help\"\n\" \" = \"quit\"\n",
            4,
            "line 2",
        ),
        (
            "repeated",
            "[race]\nx = \"stop\"\nx = \"help\"\n",
            3,
            "duplicate key",
        ),
        ("not_string", "[load]\nx = true\n", 2, "boolean"),
    ];
    for (kind, text, line, detail) in cases {
        let message = load_bad(kind, text);
        assert!(
            message.contains(&format!("bad.toml:{line}:")),
            "{kind}: {message}"
        );
        assert!(message.contains(detail), "{kind}: {message}");
    }
}

#[test]
fn a_missing_file_is_an_error_naming_it() {
    let path = keymaps_dir().join("no_such_keymap.toml");
    let err = Keymap::load(&path).unwrap_err();
    assert!(matches!(err, KeymapError::Read { .. }));
    assert!(err.to_string().contains("no_such_keymap.toml"), "{err}");
}
