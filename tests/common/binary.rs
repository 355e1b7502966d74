//! The navdeck binary, run as a user runs it.

/// Runs the navdeck binary with `args`, without colour, and waits for it.
pub fn navdeck(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_navdeck"))
        .args(args)
        .env("NO_COLOR", "1")
        .output()
        .expect("navdeck runs")
}
