//! Keymap overlays.

use super::{Case, case};

pub fn cases() -> Vec<Case> {
    let headless = |file: &str| {
        vec![
            "--keymap".to_string(),
            file.to_string(),
            "--headless".to_string(),
            "--keys".to_string(),
            "w".to_string(),
        ]
    };
    let keymap = |names: &str, body: &str| {
        let mut c = case("keymap", &[], names).file("k.toml", body);
        c.args = headless("k.toml");
        c
    };
    vec![
        keymap("quit", "[global]\nq = \"none\"\nctrl-c = \"none\"\n"),
        keymap("fly", "[global]\nx = \"fly\"\n"),
        keymap("k.toml", "[global\n"),
        keymap("warp", "[warp]\nw = \"forward\"\n"),
        keymap("florp", "[global]\nflorp = \"quit\"\n"),
        {
            let mut c = case("keymap", &[], "/dev/zero");
            c.args = headless("/dev/zero");
            c
        },
    ]
}
