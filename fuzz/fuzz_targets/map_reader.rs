//! Fuzzes the map file reader: the input is a map's YAML and its PGM image, split at the
//! first NUL byte. Any input must give a map or an error, never a crash or a huge
//! allocation.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let split = data.iter().position(|&b| b == 0).unwrap_or(data.len());
    let (yaml, image) = (&data[..split], data.get(split + 1..).unwrap_or_default());
    let text = String::from_utf8_lossy(yaml);
    let _ = navdeck::map::io::decode(&text, Path::new("fuzz.yaml"), &mut |_| Ok(image.to_vec()));
});
