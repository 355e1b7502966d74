//! Fuzzes the world file reader: the input, as lossy UTF-8, is a world file's TOML. Any
//! input must give a world or an error, never a crash or a huge allocation.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let _ = navdeck::sim::World::from_toml(&text, Path::new("fuzz.toml"));
});
