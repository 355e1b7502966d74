//! The README's examples must work as written.

use navdeck::config::Config;
use std::path::Path;

const README: &str = include_str!("../README.md");

#[test]
fn readme_config_example_parses() {
    let start = README.find("```toml\n").expect("a toml example") + "```toml\n".len();
    let len = README[start..].find("```").unwrap();
    let config = Config::parse(&README[start..start + len], Path::new("README.md")).unwrap();
    assert_eq!(config.sim.lidar.beams, 180);
    assert_eq!(config.teleop.deadman_timeout, 0.4);
}

#[test]
fn readme_gives_the_two_set_up_commands() {
    assert!(README.contains("cargo run --release"));
    assert!(README.contains("./scripts/test"));
}

#[test]
fn every_readme_config_example_parses() {
    let mut rest = README;
    let mut count = 0;
    while let Some(start) = rest.find("```toml\n") {
        let body = &rest[start + "```toml\n".len()..];
        let len = body.find("```").unwrap();
        if let Err(e) = Config::parse(&body[..len], Path::new("README.md")) {
            panic!("README toml example {count} does not parse: {e}");
        }
        count += 1;
        rest = &body[len..];
    }
    assert!(count >= 3, "{count} examples");
}

/// The first column of each row of the README's key table: the keys it names.
fn readme_key_cells() -> Vec<String> {
    let start = README
        .find("| key | action |")
        .expect("the README's key table");
    README[start..]
        .lines()
        .skip(2)
        .take_while(|l| l.starts_with('|'))
        .map(|l| l.split('|').nth(1).unwrap_or_default().to_string())
        .collect()
}

/// The keys written in backticks in a cell.
fn backticked(cell: &str) -> Vec<String> {
    cell.split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_string)
        .collect()
}

#[test]
fn the_readme_key_table_names_every_key_the_help_shows_and_no_other() {
    use navdeck::keymap::{Key, Keymap};
    use navdeck::pilot::mode::Mode;
    let cells = readme_key_cells();
    let written: Vec<String> = cells.iter().flat_map(|c| backticked(c)).collect();
    let says_arrows = cells.iter().any(|c| c.contains("arrows"));
    let map = Keymap::default_map();
    let mut bound: Vec<Key> = Vec::new();
    for mode in Mode::ALL {
        for (action, keys) in map.bindings(mode) {
            for key in keys {
                let name = key.to_string();
                let arrow = ["left", "right", "up", "down"].contains(&name.as_str());
                assert!(
                    written.contains(&name) || (arrow && says_arrows),
                    "the help shows `{name}` ({}) in {mode:?} mode; the README's key table does not",
                    action.name()
                );
                bound.push(key);
            }
        }
    }
    for name in &written {
        let key: Key = name
            .parse()
            .unwrap_or_else(|e| panic!("README key table: `{name}` is not a key: {e}"));
        assert!(
            bound.contains(&key),
            "the README's key table names `{name}`, which no mode binds"
        );
    }
}
