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
