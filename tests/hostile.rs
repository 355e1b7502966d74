//! A corpus of hostile inputs run against the built binary, each as a user would meet it:
//! under a 20 s time limit and a 2 GiB address-space limit, every case must end with an
//! exit status from 1 to 99, a message naming what was wrong, no panic, and no raw
//! escape character in what reaches the terminal.
//!
//! The config cases are made from navdeck's own default config: every number in it,
//! set to NaN, 1e308 and -1e308 in turn, so a field added later is covered at once.

use std::path::Path;
use std::process::Command;

/// One hostile input: the files it writes, the command line, and a text the error must
/// contain (the field, file or option at fault).
struct Case {
    kind: &'static str,
    files: Vec<(String, Vec<u8>)>,
    args: Vec<String>,
    names: String,
}

fn case(kind: &'static str, args: &[&str], names: &str) -> Case {
    Case {
        kind,
        files: Vec::new(),
        args: args.iter().map(|s| s.to_string()).collect(),
        names: names.to_string(),
    }
}

impl Case {
    fn file(mut self, name: &str, body: impl Into<Vec<u8>>) -> Case {
        self.files.push((name.to_string(), body.into()));
        self
    }
}

/// What running a case gave: exit status, and standard output and error.
struct Outcome {
    code: Option<i32>,
    out: String,
    err: String,
}

/// Runs `case` in its own folder under `root`, `{dir}` in its arguments standing for it.
fn run(case: &Case, root: &Path, n: usize) -> Outcome {
    let dir = root.join(format!("case-{n}"));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, body) in &case.files {
        std::fs::write(dir.join(name), body).unwrap();
    }
    let args: Vec<String> = case
        .args
        .iter()
        .map(|a| a.replace("{dir}", dir.to_str().unwrap()))
        .collect();
    // The limits the bar names: 2 GiB of address space, 20 s.
    let output = Command::new("sh")
        .arg("-c")
        .arg("ulimit -v 2097152; exec timeout 20 \"$@\"")
        .arg("sh")
        .arg(env!("CARGO_BIN_EXE_navdeck"))
        .args(&args)
        .current_dir(&dir)
        .output()
        .expect("sh runs");
    Outcome {
        code: output.status.code(),
        out: String::from_utf8_lossy(&output.stdout).into_owned(),
        err: String::from_utf8_lossy(&output.stderr).into_owned(),
    }
}

/// Every number of the default config as (table, key, array index).
fn numeric_fields() -> Vec<(String, String, Option<usize>)> {
    let text = toml::to_string(&navdeck::config::Config::default()).unwrap();
    let root: toml::Table = text.parse().unwrap();
    let mut out = Vec::new();
    fn walk(table: &toml::Table, path: &str, out: &mut Vec<(String, String, Option<usize>)>) {
        for (key, value) in table {
            match value {
                toml::Value::Table(t) => {
                    let sub = if path.is_empty() {
                        key.clone()
                    } else {
                        format!("{path}.{key}")
                    };
                    walk(t, &sub, out);
                }
                toml::Value::Integer(_) | toml::Value::Float(_) => {
                    out.push((path.to_string(), key.clone(), None));
                }
                toml::Value::Array(items)
                    if !items.is_empty() && items.iter().all(|v| v.is_float()) =>
                {
                    out.push((path.to_string(), key.clone(), Some(0)));
                }
                _ => {}
            }
        }
    }
    walk(&root, "", &mut out);
    out
}

fn config_cases() -> Vec<Case> {
    let plan = [
        "plan", "--config", "bad.toml", "--from", "0,0", "--to", "0.2,0",
    ];
    let deep =
        |open: &str, close: &str| format!("x = {}1{}\n", open.repeat(50_000), close.repeat(50_000));
    let mut cases = vec![
        case("config", &plan, "recursion").file("bad.toml", deep("[", "]")),
        case("config", &plan, "recursion").file("bad.toml", deep("{a = ", "}")),
        case("config", &plan, "bad.toml").file("bad.toml", vec![0xff, 0xfe, 0x00]),
        case("config", &plan, "limit").file("bad.toml", "#".repeat(2 << 20)),
        case(
            "config",
            &[
                "plan",
                "--config",
                "/dev/urandom",
                "--from",
                "0,0",
                "--to",
                "1,0",
            ],
            "regular file",
        ),
    ];
    for (table, key, index) in numeric_fields() {
        for value in ["nan", "1e308", "-1e308"] {
            let setting = match index {
                None => format!("{key} = {value}"),
                Some(_) => format!("{key} = [{value}, 0.0, 0.0]"),
            };
            let body = format!("[{table}]\n{setting}\n");
            cases.push(
                case(
                    "config",
                    &[
                        "plan", "--config", "bad.toml", "--from", "0,0", "--to", "0.2,0",
                    ],
                    &key,
                )
                .file("bad.toml", body),
            );
        }
    }
    cases
}

/// The built-in arena's world file with `line` (starting with `key =`) replaced, or
/// `extra` appended.
fn arena_with(key: &str, line: &str) -> String {
    let arena = include_str!("../maps/arena.toml");
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

fn world_cases() -> Vec<Case> {
    let arena = include_str!("../maps/arena.toml").to_string();
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

/// A valid Nav2 map header naming `image`, with `extra` lines.
fn map_yaml(image: &str, resolution: &str, extra: &str) -> String {
    format!(
        "image: {image}\nresolution: {resolution}\norigin: [0.0, 0.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n{extra}"
    )
}

fn map_cases() -> Vec<Case> {
    let info = ["map", "info", "m.yaml"];
    let pgm = b"P5 4 4 255\n"
        .iter()
        .copied()
        .chain([254u8; 16])
        .collect::<Vec<u8>>();
    let map = |names: &str, yaml: String| {
        case("map", &info, names)
            .file("m.yaml", yaml)
            .file("m.pgm", pgm.clone())
    };
    vec![
        map("resolution", map_yaml("m.pgm", "1e308", "")),
        map("resolution", map_yaml("m.pgm", "nan", "")),
        map("resolution", map_yaml("m.pgm", "-0.05", "")),
        map("resolution", map_yaml("m.pgm", "1e-300", "")),
        map(
            "origin",
            map_yaml("m.pgm", "0.05", "").replace("[0.0, 0.0, 0.0]", "[1e308, 0, 0]"),
        ),
        map(
            "limit",
            format!(
                "image: {}m.pgm{}\n",
                "[".repeat(100_000),
                "]".repeat(100_000)
            ),
        ),
        map(
            "nested",
            format!("image: {}m.pgm{}\n", "[".repeat(10_000), "]".repeat(10_000)),
        ),
        map(
            "m.yaml",
            "image: m.pgm\n".to_string() + &"  ".repeat(40_000) + "x: 1\n",
        ),
        map("/dev/zero", map_yaml("/dev/zero", "0.05", "")),
        map(
            "free_thresh",
            map_yaml("m.pgm", "0.05", "").replace("0.196", "nan"),
        ),
        map(
            "negate",
            map_yaml("m.pgm", "0.05", "").replace("negate: 0", "negate: 7"),
        ),
        case("map", &info, "width")
            .file("m.yaml", map_yaml("m.pgm", "0.05", ""))
            .file("m.pgm", b"P5 20000 20000 255\n".to_vec()),
        case("map", &info, "truncated")
            .file("m.yaml", map_yaml("m.pgm", "0.05", ""))
            .file("m.pgm", b"P2 8000 8000 255\n1 2 3".to_vec()),
        case("map", &["map", "info", "/dev/zero"], "/dev/zero"),
        case("map", &["map", "info", "{dir}"], "regular file"),
        case(
            "map",
            &[
                "plan", "--map", "m.yaml", "--from", "0,0", "--to", "0.1,0.1",
            ],
            "resolution",
        )
        .file("m.yaml", map_yaml("m.pgm", "1e308", ""))
        .file("m.pgm", pgm.clone()),
    ]
}

fn keymap_cases() -> Vec<Case> {
    let headless = |file: &str| {
        vec![
            "--keymap".to_string(),
            file.to_string(),
            "--headless".to_string(),
            "--keys".to_string(),
            "w".to_string(),
        ]
    };
    let keymap = |names: &str, body: &str| Case {
        kind: "keymap",
        files: vec![("k.toml".into(), body.as_bytes().to_vec())],
        args: headless("k.toml"),
        names: names.into(),
    };
    vec![
        keymap("quit", "[global]\nq = \"none\"\nctrl-c = \"none\"\n"),
        keymap("fly", "[global]\nx = \"fly\"\n"),
        keymap("k.toml", "[global\n"),
        keymap("warp", "[warp]\nw = \"forward\"\n"),
        keymap("florp", "[global]\nflorp = \"quit\"\n"),
        Case {
            kind: "keymap",
            files: Vec::new(),
            args: headless("/dev/zero"),
            names: "/dev/zero".into(),
        },
    ]
}

fn cli_cases() -> Vec<Case> {
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
    ]
}

#[cfg(feature = "vision")]
fn calibration_cases() -> Vec<Case> {
    let calib = |fx: &str, cx: &str, width: &str, dist: &str| {
        format!(
            "%YAML:1.0\n---\nimage_width: {width}\nimage_height: 480\ncamera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n   data: [ {fx}, 0., {cx}, 0., 600., 240., 0., 0., 1. ]\ndistortion_coefficients: !!opencv-matrix\n   rows: 1\n   cols: 5\n   dt: d\n   data: [ {dist}, 0., 0., 0., 0. ]\n"
        )
    };
    let args = [
        "--sim-camera",
        "--config",
        "c.toml",
        "--headless",
        "--keys",
        "w",
    ];
    let config = "[vision]\ncalibration = \"cam.yml\"\n";
    let with = |names: &str, body: String| {
        case("calibration", &args, names)
            .file("c.toml", config)
            .file("cam.yml", body)
    };
    vec![
        with("cx", calib("600.", ".nan", "640", "0.")),
        with("cx", calib("600.", "1e308", "640", "0.")),
        with("fx", calib("-600.", "320.", "640", "0.")),
        with("fx", calib("1e308", "320.", "640", "0.")),
        with("distortion", calib("600.", "320.", "640", ".nan")),
        with("image_width", calib("600.", "320.", "wide", "0.")),
        with("image_width", calib("600.", "320.", "2000000000", "0.")),
        // Found by fuzzing: OpenCV 4.6's FileStorage parser never returns on this file.
        with(
            "did not finish",
            include_str!("hostile_inputs/calibration_parser_loop.yml").to_string(),
        ),
        case("calibration", &args, "/dev/zero")
            .file("c.toml", "[vision]\ncalibration = \"/dev/zero\"\n"),
    ]
}

#[cfg(not(feature = "vision"))]
fn calibration_cases() -> Vec<Case> {
    Vec::new()
}

/// Recordings for `navdeck replay`: not MCAP, empty, endless, a folder, and two files the
/// fuzzer made whose chunks and records claim sizes they do not have.
fn recording_cases() -> Vec<Case> {
    let replay = |names: &str, body: Vec<u8>| {
        case("recording", &["replay", "r.mcap", "--headless"], names).file("r.mcap", body)
    };
    let inputs = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/hostile_inputs/");
    let mut out = vec![
        replay(
            "not an MCAP file",
            b"\x1b]2;owned\x07 not a recording".to_vec(),
        ),
        replay("not an MCAP file", Vec::new()),
        replay("offset 8", b"\x89MCAP0\r\n".to_vec()),
        replay(
            "offset 8",
            [
                b"\x89MCAP0\r\n".as_slice(),
                &[6, 255, 255, 255, 255, 255, 255, 255, 127],
            ]
            .concat(),
        ),
        case(
            "recording",
            &["replay", "/dev/zero", "--headless"],
            "/dev/zero",
        ),
        case(
            "recording",
            &["replay", "{dir}", "--headless"],
            "regular file",
        ),
        case(
            "recording",
            &["replay", "missing.mcap", "--headless"],
            "missing.mcap",
        ),
    ];
    for name in ["recording_chunk_lies.mcap", "recording_record_lies.mcap"] {
        let body = std::fs::read(format!("{inputs}{name}")).unwrap();
        out.push(replay("offset", body));
    }
    out
}

#[test]
fn every_hostile_input_is_refused_cleanly_naming_what_is_wrong() {
    let root = std::env::temp_dir().join(format!("navdeck-hostile-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    let mut cases = config_cases();
    cases.extend(world_cases());
    cases.extend(map_cases());
    cases.extend(keymap_cases());
    cases.extend(cli_cases());
    cases.extend(calibration_cases());
    cases.extend(recording_cases());
    let mut counts = std::collections::BTreeMap::new();
    for c in &cases {
        *counts.entry(c.kind).or_insert(0usize) += 1;
    }
    eprintln!("hostile corpus: {} cases {counts:?}", cases.len());
    assert!(cases.len() >= 150);
    // Two at a time: the machine the suite runs on has two cores.
    let failures: Vec<String> = std::thread::scope(|s| {
        let halves: Vec<_> = [0, 1]
            .into_iter()
            .map(|half| {
                let (cases, root) = (&cases, &root);
                s.spawn(move || {
                    let mut failures = Vec::new();
                    for (n, c) in cases.iter().enumerate().filter(|(n, _)| n % 2 == half) {
                        if let Some(why) = judge(c, &run(c, root, n)) {
                            failures.push(format!("{} {:?}: {why}", c.kind, c.args));
                        }
                    }
                    failures
                })
            })
            .collect();
        halves.into_iter().flat_map(|h| h.join().unwrap()).collect()
    });
    let _ = std::fs::remove_dir_all(&root);
    assert!(
        failures.is_empty(),
        "{} of {} cases failed:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}

/// Why `outcome` breaks the bar for `case`, if it does.
fn judge(case: &Case, o: &Outcome) -> Option<String> {
    let said = format!("{}{}", o.out, o.err);
    let first_line = o.err.lines().next().unwrap_or_default().to_string();
    match o.code {
        Some(code) if (1..=99).contains(&code) => {}
        Some(124) => return Some("killed after 20 s".into()),
        other => return Some(format!("exit {other:?}: {first_line}")),
    }
    if said.contains("panicked") {
        return Some(format!("panicked: {first_line}"));
    }
    if said.contains('\u{1b}') {
        return Some("a raw escape character reached the terminal".into());
    }
    if !said.contains(&case.names) {
        return Some(format!("does not name `{}`: {first_line}", case.names));
    }
    None
}
