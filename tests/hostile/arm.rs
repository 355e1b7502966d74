//! The arm's config section and the `navdeck arm` numbers, and numbers printed short in
//! range messages everywhere. Every number of the default `[arm]` is set in turn to NaN,
//! ±inf, ±1e308 (each refused, naming the field), 1e-300, 0 and -1 (refused naming it, or
//! a pick that ends cleanly); every `arm` argument gets the same values.

use super::{Case, case};

/// Hostile values: those no field may take, then those some fields may.
const NEVER: [&str; 5] = ["nan", "inf", "-inf", "1e308", "-1e308"];
const MAYBE: [&str; 3] = ["1e-300", "0", "-1"];

/// Every number of the default `[arm]`: (table under `arm`, key, default array or none).
fn arm_fields() -> Vec<(String, String, Option<Vec<String>>)> {
    let arm = navdeck::arm::ArmConfig::default();
    let root: toml::Table = toml::to_string(&arm).unwrap().parse().unwrap();
    let mut out = Vec::new();
    fn walk(table: &toml::Table, path: &str, out: &mut Vec<(String, String, Option<Vec<String>>)>) {
        for (key, value) in table {
            match value {
                toml::Value::Table(t) => walk(t, &format!("{path}.{key}"), out),
                toml::Value::Integer(_) | toml::Value::Float(_) => {
                    out.push((path.to_string(), key.clone(), None));
                }
                toml::Value::Array(items) => {
                    let items = items.iter().map(ToString::to_string).collect();
                    out.push((path.to_string(), key.clone(), Some(items)));
                }
                _ => {}
            }
        }
    }
    walk(&root, "arm", &mut out);
    out
}

/// `navdeck arm pick-test` with `body` as its config.
fn pick(names: &str, body: String) -> Case {
    let args = [
        "arm",
        "pick-test",
        "--picks",
        "1",
        "--json",
        "--config",
        "bad.toml",
    ];
    case("arm", &args, names).file("bad.toml", body)
}

fn config_cases() -> Vec<Case> {
    let mut cases = Vec::new();
    for (table, key, array) in arm_fields() {
        for (k, value) in NEVER.iter().chain(&MAYBE).enumerate() {
            let setting = match &array {
                None => format!("{key} = {value}"),
                Some(items) => {
                    // Each value lands on another element in turn.
                    let mut items = items.clone();
                    let at = k % items.len();
                    items[at] = value.to_string();
                    format!("{key} = [{}]", items.join(", "))
                }
            };
            let c = pick(&key, format!("[{table}]\n{setting}\n"));
            cases.push(if MAYBE.contains(value) {
                c.or_clean()
            } else {
                c
            });
        }
    }
    // The issue's: speeds that made a pick run for ever, links of nothing.
    for speed in ["1e-300", "1e-6", "0.001"] {
        let body = format!("[arm.limits]\nspeed = [{speed}, 4.8, 4.8, 4.8]\n");
        cases.push(pick("limits.speed[0]` = ", body));
    }
    cases.push(pick(
        "arm.links[1]` = 1e-300: must lie in 0.01..=2",
        "[arm]\nlinks = [0.13, 1e-300, 0.15]\n".into(),
    ));
    // An integer field printed as one, in any section.
    cases.push(pick(
        "max_iterations = 1e308",
        "[arm.refine]\nmax_iterations = 1e308\n".into(),
    ));
    cases.push(pick(
        "floating point `1e308`",
        "[arm.refine]\nmax_iterations = 1e308\n".into(),
    ));
    cases
}

fn cli_cases() -> Vec<Case> {
    let mut cases = Vec::new();
    // fk: each joint in turn; the 1e308 on all four.
    cases.push(case(
        "arm",
        &["arm", "fk", "1e308", "1e308", "1e308", "1e308"],
        "J1 (base yaw) = 1e308 rad is outside its limits -2.82743..=2.82743 rad",
    ));
    for j in 0..4 {
        for value in NEVER.iter().chain(&MAYBE).chain(&["-4", "7"]) {
            let mut args = vec!["arm", "fk", "0", "0", "0", "0"];
            args[2 + j] = value;
            let c = case("arm", &args, &format!("J{}", j + 1));
            cases.push(if MAYBE.contains(value) {
                c.or_clean()
            } else {
                c
            });
        }
    }
    // ik: each coordinate in turn, and the pitch.
    for (k, name) in ["<X>", "<Y>", "<Z>"].into_iter().enumerate() {
        for value in NEVER.iter().chain(&["7.5", "-100"]) {
            let mut args = vec!["arm", "ik", "0.2", "0", "0.1"];
            args[2 + k] = value;
            cases.push(case("arm", &args, name));
        }
        for value in MAYBE {
            let mut args = vec!["arm", "ik", "0.2", "0", "0.1", "--json"];
            args[2 + k] = value;
            cases.push(case("arm", &args, "\"reachable\":false").or_clean());
        }
    }
    for value in NEVER.iter().chain(&["361", "-1000"]) {
        let pitch = format!("--pitch={value}");
        cases.push(case(
            "arm",
            &["arm", "ik", "0.2", "0", "0.1", &pitch],
            "--pitch",
        ));
    }
    for value in MAYBE {
        let args = ["arm", "ik", "0.2", "0", "0.1", "--pitch", value];
        cases.push(case("arm", &args, "unreachable").or_clean());
    }
    // The tool on joint 1's axis: solved, with a warning, never NaN.
    cases.push(case("arm", &["arm", "ik", "0", "0", "0", "--json"], "ik").or_clean());
    // pick-test's counts.
    for value in [
        "0",
        "-1",
        "10001",
        "1e308",
        "nan",
        "18446744073709551616",
        "",
    ] {
        let picks = format!("--picks={value}");
        cases.push(case("arm", &["arm", "pick-test", &picks], "--picks"));
    }
    for value in ["-1", "nan", "1e308", "18446744073709551616"] {
        let seed = format!("--seed={value}");
        let args = ["arm", "pick-test", "--picks", "1", &seed];
        cases.push(case("arm", &args, "--seed"));
    }
    // Empty bands and unseen blocks: no -0.0, no null.
    cases.push(case("arm", &["arm", "pick-test", "--picks", "1", "--json"], "").or_clean());
    cases
}

/// Range messages elsewhere print their numbers short, with a range that holds.
fn short_number_cases() -> Vec<Case> {
    let fk_config = ["arm", "fk", "0", "0", "0", "0", "--config", "bad.toml"];
    let tour = |duration: &str| {
        let option = format!("--duration={duration}");
        let args = ["tour", "--world", "maps/flat.yaml", &option];
        case(
            "numbers",
            &args,
            &format!("{duration} s is outside 0.1..=7200"),
        )
    };
    let mut cases = vec![
        tour("0"),
        tour("1e308"),
        tour("-1e308"),
        tour("1e-300"),
        case(
            "numbers",
            &["plan", "--from", "0,0", "--to", "1e308,0"],
            "goal (1e308, 0.000)",
        ),
        case(
            "numbers",
            &["plan", "--from", "-1e308,0", "--to", "0,0"],
            "(-1e308, 0.000)",
        ),
        case(
            "numbers",
            &[
                "world", "generate", "--seed", "1", "--size", "1e308,4", "-o", "w.toml",
            ],
            "--size 1e308,4",
        ),
        case(
            "numbers",
            &["ros2", "topics", "--duration", "1e308"],
            "1e308 s is outside 0.1..=3600",
        ),
        case(
            "numbers",
            &["mission", "--time-limit=-1e308"],
            "-1e308 s is outside 1..=7200",
        ),
        case("numbers", &fk_config, "`robot.track` = 1e308: must lie in")
            .file("bad.toml", "[robot]\ntrack = 1e308\n"),
        case(
            "numbers",
            &fk_config,
            "`record.level` = 0: must lie in 1..=19",
        )
        .file("bad.toml", "[record]\nlevel = 0\n"),
        case(
            "numbers",
            &fk_config,
            "`record.level` = 19: must lie in 1..=12 with compression = \"lz4\"",
        )
        .file("bad.toml", "[record]\ncompression = \"lz4\"\nlevel = 19\n"),
        case("numbers", &fk_config, "record.level")
            .file("bad.toml", "[record]\ncompression = \"lz4\"\nlevel = 13\n"),
        case("numbers", &fk_config, "floating point `-1e308`")
            .file("bad.toml", "[sim.lidar]\nbeams = -1e308\n"),
    ];
    // The world's own size (the first `size =` line; obstacles' come later).
    let world = include_str!("../../maps/arena.toml").replacen(
        "size = [4.0, 4.0]",
        "size = [1e308, 4.0]",
        1,
    );
    cases.push(
        case(
            "numbers",
            &["mission", "--world", "w.toml", "--time-limit", "5"],
            "= 1e308: must lie in",
        )
        .file("w.toml", world),
    );
    cases
}

pub fn cases() -> Vec<Case> {
    let mut cases = config_cases();
    cases.extend(cli_cases());
    cases.extend(short_number_cases());
    cases
}
