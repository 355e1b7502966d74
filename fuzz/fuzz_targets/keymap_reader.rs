//! Fuzzes the keymap overlay reader: the input, as lossy UTF-8, is a keymap file's TOML
//! laid over the defaults. Any input must give a keymap or an error, never a crash.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let _ = navdeck::keymap::Keymap::parse_overlay(&text, Path::new("fuzz.toml"));
});
