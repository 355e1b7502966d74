//! World files: the arena with one line made hostile.

use super::{Case, case};

/// The built-in arena's world file with `line` (starting with `key =`) replaced, or
/// `extra` appended.
fn arena_with(key: &str, line: &str) -> String {
    let arena = include_str!("../../maps/arena.toml");
    arena
        .lines()
        .map(|l| {
            if l.starts_with(&format!("{key} =")) {
                line.to_string()
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

pub fn cases() -> Vec<Case> {
    let arena = include_str!("../../maps/arena.toml").to_string();
    let mission = ["mission", "--world", "w.toml", "--time-limit", "5"];
    let world = |names: &str, body: String| case("world", &mission, names).file("w.toml", body);
    let block = |x: f64, y: f64, size: f64| {
        format!(
            "\n[[blocks]]\ncolor = \"blue\"\nx = {x}\ny = {y}\nsize = {size}\nmarkers = [523, 524]\n"
        )
    };
    vec![
        world("size", arena_with("size", "size = [1000.0, 1000.0]")),
        world("size", arena_with("size", "size = [1e-300, 1e-300]")),
        world("size", arena_with("size", "size = [nan, 4.0]")),
        world("size", arena_with("size", "size = [-4.0, 4.0]")),
        world(
            "resolution",
            "name = \"hall\"\nsize = [90.0, 90.0]\nstart = [0.0, 0.0, 0.0]\n[[walls]]\npoints = [[-44.0, -44.0], [44.0, -44.0], [44.0, 44.0], [-44.0, 44.0]]\nclosed = true\n".to_string(),
        ),
        world("wall", arena_with("start", "start = [-2.0, -1.5, 0.0]")),
        world("footprint", arena_with("start", "start = [-1.95, -1.5, 0.0]")),
        world("obstacles[0]", arena_with("start", "start = [0.5, 0.5, 0.0]")),
        world("start", arena_with("start", "start = [nan, 0.0, 0.0]")),
        world("start", arena_with("start", "start = [1e308, 0.0, 0.0]")),
        world("blocks[0]", arena_with("start", "start = [1.0, -0.2, 0.0]")),
        world("obstacles[0]", arena.clone() + &block(0.5, 0.5, 0.05).replace("523, 524", "525, 526")),
        world("overlaps", arena.clone() + &block(1.0, -0.2, 0.05).replace("523, 524", "525, 526")),
        world("blocks[4]", arena.clone() + &block(0.0, 0.0, 100.0).replace("523, 524", "525, 526")),
        world("name", arena_with("name", "name = \"arena\\u001b]2;owned\\u0007\"")),
        world("name", arena_with("name", &format!("name = \"{}\"", "x".repeat(500)))),
        world("gates[0]", arena.replace("center = [2.0, 1.0]", "center = [1.0, 1.0]")),
        world("w.toml", "\u{0}\u{1}garbage".to_string()),
        world("w.toml", String::new()),
        world("w.toml", format!("name = \"x\"\n{}", "# padding\n".repeat(600_000))),
        case("world", &["mission", "--world", "/dev/zero"], "/dev/zero"),
        case("world", &["mission", "--world", "{dir}"], "regular file"),
        case("world", &["mission", "--world", "missing.toml"], "missing.toml"),
        case(
            "world",
            &["--world", concat!(env!("CARGO_MANIFEST_DIR"), "/maps/turtlebot3_world.yaml"), "--start", "0,0,0", "--headless"],
            "start",
        ),
        case("world", &["--start", "0.5,0.5,0", "--headless"], "obstacles[0]"),
        case("world", &["--start", "nan,0,0", "--headless"], "--start"),
        case("world", &["--start", "9,9,0", "--headless"], "outside the world"),
        world("w.toml", "[[walls]]\n".repeat(10_000)),
    ]
}
