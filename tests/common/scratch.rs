//! Scratch folders for the files a test writes.

use std::path::PathBuf;

/// An empty folder for a test's files: `navdeck-<test file>-<process id>-<name>` in the
/// system's temporary folder, emptied first (a process id comes round again). The tests of
/// a file run at once, so each takes a `name` of its own.
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "navdeck-{}-{}-{name}",
        env!("CARGO_CRATE_NAME"),
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}
