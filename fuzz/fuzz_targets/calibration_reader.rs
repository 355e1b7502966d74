//! Fuzzes the camera calibration reader (feature `vision`): the input is an OpenCV
//! FileStorage file, written to a temporary file of this process and read back with
//! `calibration::load`. Any input must give intrinsics or an error, never a crash.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::PathBuf;
use std::sync::OnceLock;

/// One file per fuzzing process, so parallel jobs do not overwrite each other's input.
fn scratch() -> &'static PathBuf {
    static PATH: OnceLock<PathBuf> = OnceLock::new();
    PATH.get_or_init(|| {
        std::env::temp_dir().join(format!(
            "navdeck-fuzz-calibration-{}.yml",
            std::process::id()
        ))
    })
}

fuzz_target!(|data: &[u8]| {
    let path = scratch();
    std::fs::write(path, data).expect("the temporary calibration file can be written");
    let _ = navdeck::perception::calibration::load(path);
});
