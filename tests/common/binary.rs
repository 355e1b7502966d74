//! The navdeck binary, run as a user runs it.

/// Runs the navdeck binary with `args`, without colour, and waits for it.
pub fn navdeck(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_navdeck"))
        .args(args)
        .env("NO_COLOR", "1")
        .output()
        .expect("navdeck runs")
}

/// `navdeck mission --generated --style STYLE --seed SEED --json EXTRA...`: its report.
pub fn generated_mission(style: &str, seed: &str, extra: &[&str]) -> serde_json::Value {
    let mut args = vec![
        "mission",
        "--generated",
        "--style",
        style,
        "--seed",
        seed,
        "--json",
    ];
    args.extend(extra);
    let out = navdeck(&args);
    serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(&out.stderr)))
}
