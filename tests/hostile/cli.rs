//! Command-line options.

use super::{Case, case};

pub fn cases() -> Vec<Case> {
    vec![
        case("cli", &["--seed", "-1"], "--seed"),
        case("cli", &["mission", "--seed", "-1"], "--seed"),
        case("cli", &["mission", "--time-limit", "-5"], "--time-limit"),
        case("cli", &["mission", "--time-limit", "nan"], "--time-limit"),
        case("cli", &["mission", "--sweep", "5..1"], "backwards"),
        case(
            "cli",
            &["mission", "--sweep", "1..18446744073709551615"],
            "at most",
        ),
        case("cli", &["mission", "--time-limit", "1e9"], "--time-limit"),
        case(
            "cli",
            &[
                "--headless",
                "--key-rate",
                "0.1",
                "--keys",
                &"w".repeat(1000),
            ],
            "--keys",
        ),
        case("cli", &["--headless", "--key-rate", "1e-300"], "--key-rate"),
        case("cli", &["--headless", "--key-rate", "inf"], "--key-rate"),
        case("cli", &["--domain", "999", "--link", "ros2"], "--domain"),
        case("cli", &["--config", "x.toml", "mission"], "--config"),
        case(
            "cli",
            &["--headless", "--keys", ":save ../../etc/x<enter>"],
            "map not saved",
        ),
        case("cli", &["plan", "--from", "nan,0", "--to", "0,0"], "--from"),
        case("cli", &["--link", "serial:/dev/null@0"], "baud"),
        case(
            "cli",
            &[
                "--world",
                "maps/flat.yaml",
                "--estimator",
                "mcl",
                "--initial-pose",
                "nan,0,0",
            ],
            "--initial-pose",
        ),
        case(
            "cli",
            &[
                "--world",
                "maps/flat.yaml",
                "--estimator",
                "mcl",
                "--initial-pose",
                "1e9,0,0",
            ],
            "--initial-pose",
        ),
        case(
            "cli",
            &["--estimator", "mcl", "--map", "/dev/zero"],
            "/dev/zero",
        ),
        case(
            "cli",
            &["tour", "--world", "maps/flat.yaml", "--duration", "1e9"],
            "--duration",
        ),
        case(
            "cli",
            &["tour", "--world", "maps/flat.yaml", "--kidnap", "nan@0,0,0"],
            "--kidnap",
        ),
        case(
            "cli",
            &["tour", "--world", "maps/flat.yaml", "--goals", "1,2;x,3"],
            "--goals",
        ),
        case("cli", &["--headless", "--fault", "camera@1e308"], "start"),
        case("cli", &["mission", "--fault", "slip@0+1:nan"], "slip ratio"),
        case("cli", &["tour", "--fault", "odom@0+-1"], "duration"),
        case(
            "cli",
            &["mission", "--fault", "lidar\u{7}@1"],
            "unknown sensor",
        ),
        case(
            "cli",
            &["--link", "serial:/dev/null", "--fault", "arm@1"],
            "--fault",
        ),
    ]
}
