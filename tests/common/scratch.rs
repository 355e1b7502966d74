//! Scratch folders for the files a test writes.

use std::path::{Path, PathBuf};

/// An empty folder for a test's files: `navdeck-<test file>-<process id>-<name>` in the
/// system's temporary folder, emptied first (a process id comes round again). Every test
/// of the suite runs in one process, at once with others, so the folder carries the name
/// of the file that asks for it, and each test of a file takes a `name` of its own.
#[track_caller]
pub fn scratch(name: &str) -> PathBuf {
    let file = Path::new(std::panic::Location::caller().file())
        .file_stem()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
    let dir = std::env::temp_dir().join(format!("navdeck-{file}-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}
