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
