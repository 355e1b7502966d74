//! Maps for MCL, the files navdeck writes, and the names and commands a user gives: huge
//! maps, maps a recording points at, planted and dangling links, names with control
//! characters, ROS 2 namespaces, poses in walls and off the map.

use super::{Case, case};
use navdeck::msgs::record::InputMsg;
use navdeck::record::{RecordConfig, Recorder, Topic};
use std::collections::BTreeMap;

/// A title-setting escape sequence, the kind a hostile name carries.
const ESCAPE: &str = "\u{1b}]0;pwn\u{7}";

/// `text` as a TOML string, control characters escaped as TOML escapes them.
fn toml_string(text: &str) -> String {
    toml::Value::String(text.to_string()).to_string()
}

/// A Nav2 map header for `image` with `origin` and `resolution`.
fn map_yaml(image: &str, resolution: &str, origin: &str) -> String {
    format!(
        "image: {image}\nresolution: {resolution}\norigin: [{origin}, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
    )
}

/// A `side` x `side` binary PGM: unknown, with a walled free room of `room` cells round
/// the centre (the whole image when `room` is `side`).
fn pgm(side: usize, room: usize) -> Vec<u8> {
    let (lo, hi) = ((side - room) / 2, (side + room) / 2 - 1);
    let mut out = format!("P5 {side} {side} 255\n").into_bytes();
    for y in 0..side {
        for x in 0..side {
            let inside = (lo..=hi).contains(&x) && (lo..=hi).contains(&y);
            let wall = inside && (x == lo || x == hi || y == lo || y == hi);
            out.push(match (inside, wall) {
                (_, true) => 0,
                (true, false) => 254,
                _ => 205,
            });
        }
    }
    out
}

/// A recording that asks for MCL and names `map` (and `world`, when given) as the map
/// it localised on, with one recorded input.
fn recording_naming(map: Option<&str>, world: Option<&str>) -> Vec<u8> {
    use std::sync::atomic::{AtomicUsize, Ordering};
    static MADE: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "navdeck-hostile-files-{}-{}",
        std::process::id(),
        MADE.fetch_add(1, Ordering::Relaxed)
    ));
    let _ = std::fs::remove_dir_all(&dir);
    let path = dir.join("r.mcap");
    let mut recorder = Recorder::create(&path, &RecordConfig::default(), 0.0).unwrap();
    let mut session = BTreeMap::new();
    session.insert("estimator".to_string(), "mcl".to_string());
    for (key, value) in [("map", map), ("world", world)] {
        if let Some(v) = value {
            session.insert(key.to_string(), v.to_string());
        }
    }
    recorder.metadata("navdeck", session);
    recorder.publish(Topic::Input, 0.0, InputMsg::resize(0.0, 80, 24));
    recorder.finish().unwrap();
    let bytes = std::fs::read(&path).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    bytes
}

/// Huge and degenerate maps given to MCL (`--map`) and as the twin's world.
fn mcl_maps() -> Vec<Case> {
    // 2048 x 2048 cells at 5 cm, centred: 102.4 m a side, 4 MB.
    let big = pgm(2048, 2048);
    let centred = map_yaml("big.pgm", "0.05", "-51.2, -51.2");
    let with_big = |args: &[&str], names: &str, yaml: &str| {
        case("mcl-map", args, names)
            .file("big.yaml", yaml)
            .file("big.pgm", big.clone())
    };
    let coarse = "[map]\nresolution = 0.05\n";
    let over = "over the limit";
    let mut out = vec![
        with_big(
            &["--estimator", "mcl", "--map", "big.yaml", "--headless"],
            over,
            &centred,
        ),
        with_big(&["--world", "big.yaml", "--headless"], "100 m", &centred),
        with_big(
            &[
                "tour",
                "--estimator",
                "mcl",
                "--map",
                "big.yaml",
                "--duration",
                "1",
            ],
            over,
            &centred,
        ),
        // The same image a kilometre from the origin, and at a metre a cell.
        with_big(
            &["--estimator", "mcl", "--map", "big.yaml", "--headless"],
            over,
            &map_yaml("big.pgm", "0.05", "-1000, -1000"),
        ),
        with_big(
            &["--estimator", "mcl", "--map", "big.yaml", "--headless"],
            over,
            &map_yaml("big.pgm", "1.0", "-1024, -1024"),
        ),
        with_big(
            &["--estimator", "mcl", "--map", "big.yaml", "--headless"],
            "origin",
            &map_yaml("big.pgm", "0.05", "-1e308, 0"),
        ),
        // On a coarse planning map the whole of it is used: MCL runs, briefly.
        with_big(
            &[
                "--config",
                "c.toml",
                "--estimator",
                "mcl",
                "--map",
                "big.yaml",
                "--headless",
                "--keys",
                "w",
            ],
            "",
            &centred,
        )
        .file("c.toml", coarse)
        .or_clean(),
        // A 4 m room in the middle of a 102 m unknown image.
        case(
            "mcl-map",
            &[
                "--config",
                "c.toml",
                "--estimator",
                "mcl",
                "--map",
                "room.yaml",
                "--headless",
                "--keys",
                "wwdd",
            ],
            "",
        )
        .file("room.yaml", map_yaml("room.pgm", "0.05", "-51.2, -51.2"))
        .file("room.pgm", pgm(2048, 80))
        .file("c.toml", coarse)
        .or_clean(),
        // A header that promises 8192 x 8192 cells and brings ten bytes.
        case(
            "mcl-map",
            &["--estimator", "mcl", "--map", "m.yaml", "--headless"],
            "m.pgm",
        )
        .file("m.yaml", map_yaml("m.pgm", "0.05", "0, 0"))
        .file(
            "m.pgm",
            [b"P5 8192 8192 255\n".as_slice(), &[254; 10]].concat(),
        ),
    ];
    // One cell: free, occupied, unknown; as MCL's map and as the world.
    for (pixel, mcl_says) in [
        (254u8, "no occupied cell"),
        (0, "no known free cell"),
        (205, "no known free cell"),
    ] {
        let one = |args: &[&str], names: &str| {
            case("mcl-map", args, names)
                .file("m.yaml", map_yaml("m.pgm", "0.05", "0, 0"))
                .file("m.pgm", [b"P5 1 1 255\n".as_slice(), &[pixel]].concat())
        };
        out.push(one(
            &["--estimator", "mcl", "--map", "m.yaml", "--headless"],
            mcl_says,
        ));
        out.push(one(&["--world", "m.yaml", "--headless"], "m.yaml"));
    }
    out.push(
        case("mcl-map", &["--world", "m.yaml", "--headless"], "too small")
            .file("m.yaml", map_yaml("m.pgm", "0.05", "0, 0"))
            .file("m.pgm", [b"P5 1 1 255\n".as_slice(), &[254]].concat()),
    );
    out
}

/// Recordings whose metadata points MCL at a file outside the folder it is replayed in.
fn recorded_maps() -> Vec<Case> {
    let replay = |map: Option<&str>, world: Option<&str>, names: &str| {
        case(
            "recorded-map",
            &["replay", "r.mcap", "--headless", "--estimator", "mcl"],
            names,
        )
        .file("r.mcap", recording_naming(map, world))
    };
    let refused = "is not read";
    vec![
        replay(Some("/etc/passwd"), None, refused),
        replay(Some("/etc/hostname.yaml"), None, refused),
        replay(Some("../m.yaml"), None, refused),
        replay(Some("maps/../../m.yaml"), None, refused),
        replay(Some("/tmp/../etc/passwd"), None, refused),
        replay(Some(""), None, refused),
        replay(None, Some("/etc/x.yaml"), refused),
        replay(None, Some("../x.yaml"), refused),
        replay(Some(&format!("{ESCAPE}.yaml")), None, "cannot read the map"),
        // A relative name is read, and a file that is not a map is refused without
        // showing what it holds.
        replay(Some("m.yaml"), None, "not a map YAML")
            .file("m.yaml", "root:x:0:0:root:/root:/bin/bash\n"),
        replay(Some("m.yaml"), None, "m.yaml").file("m.yaml", format!("{ESCAPE}: 1\n")),
        // The command line's map is used instead.
        case(
            "recorded-map",
            &[
                "replay",
                "r.mcap",
                "--headless",
                "--estimator",
                "mcl",
                "--map",
                "missing.yaml",
            ],
            "there is no such file",
        )
        .file("r.mcap", recording_naming(Some("/etc/passwd"), None)),
    ]
}

/// Folders and files navdeck creates, named with control characters or standing where a
/// file or folder is.
fn created_names() -> Vec<Case> {
    let folder = |value: &str| format!("[record]\nfolder = {}\n", toml_string(value));
    let console = |names: &str, config: String| {
        case("names", &["--config", "c.toml"], names).file("c.toml", config)
    };
    let controls = "control characters";
    let mut out = vec![
        console(controls, folder(&format!("{ESCAPE}dir"))),
        console(controls, folder(&format!("rec/{ESCAPE}"))),
        console(controls, folder("a\nb")),
        console("is a file, not a folder", folder("f")).file("f", "x"),
        console("is a file, not a folder", folder("f/sub")).file("f", "x"),
        case(
            "names",
            &["--record", &format!("{ESCAPE}.mcap"), "--headless"],
            controls,
        ),
        case(
            "names",
            &["--record", &format!("d/{ESCAPE}/r.mcap"), "--headless"],
            controls,
        ),
        case(
            "names",
            &["--record", "f/r.mcap", "--headless"],
            "is a file",
        )
        .file("f", "x"),
        case(
            "names",
            &[
                "--maps-dir",
                &format!("{ESCAPE}maps"),
                "--headless",
                "--keys",
                ":save m<enter>",
            ],
            controls,
        ),
        case(
            "names",
            &["--maps-dir", "f", "--headless", "--keys", ":save m<enter>"],
            "is a file, not a folder",
        )
        .file("f", "x"),
        case(
            "names",
            &[
                "--maps-dir",
                &format!("{ESCAPE}maps"),
                "--headless",
                "--keys",
                ":waypoint add<enter>:route save r<enter>",
            ],
            "",
        )
        .or_clean(),
        case(
            "names",
            &[
                "world",
                "generate",
                "--seed",
                "1",
                "-o",
                &format!("{ESCAPE}.toml"),
            ],
            controls,
        ),
        case(
            "names",
            &[
                "world",
                "generate",
                "--seed",
                "1",
                "-o",
                &format!("w\u{7f}{ESCAPE}/w.toml"),
            ],
            controls,
        ),
    ];
    // A map save whose temporary file is a planted link: refused, nothing left behind.
    out.push(
        case(
            "names",
            &[
                "--maps-dir",
                "{dir}",
                "--headless",
                "--keys",
                ":save m<enter>",
            ],
            "map not saved",
        )
        .link("m.yaml.tmp", "{dir}/elsewhere"),
    );
    out
}

/// `world generate -o` over links, folders, devices and missing folders.
fn world_outputs() -> Vec<Case> {
    let generate = |out: &str, names: &str| {
        case(
            "world-output",
            &["world", "generate", "--seed", "3", "-o", out],
            names,
        )
    };
    vec![
        generate("out.toml", "")
            .file("victim", "keep")
            .link("out.toml", "{dir}/victim")
            .or_clean(),
        generate("out.toml", "")
            .link("out.toml", "{dir}/nowhere/at/all")
            .or_clean(),
        generate("out.toml", "").file("out.toml", "old").or_clean(),
        generate("out.toml", "not writing through it")
            .file("victim", "keep")
            .link("out.toml.tmp", "{dir}/victim"),
        generate("{dir}", "folder"),
        generate(".", "folder"),
        generate("/dev/null", "not a regular file"),
        generate("missing/out.toml", "no such file"),
        generate("f/out.toml", "out.toml").file("f", "x"),
        generate(&"x".repeat(300), "name too long"),
        generate("loop.toml", "")
            .link("loop.toml", "{dir}/loop.toml")
            .or_clean(),
    ]
}

/// ROS 2 namespaces, given as `--ns` and as `[ros2] namespace`.
fn namespaces() -> Vec<Case> {
    let long = format!("/{}", "a".repeat(5000));
    let bad = [
        ("/1abc", "starting with a digit"),
        ("/tb3/2nd", "starting with a digit"),
        ("/a b", "' '"),
        ("/x//y", "`//`"),
        ("tb3", "start with `/`"),
        ("/tb3/", "end with `/`"),
        ("//", "end with `/`"),
        ("/a-b", "'-'"),
        ("/é", "'é'"),
        (long.as_str(), "5001 characters"),
    ];
    let mut out = Vec::new();
    for (ns, says) in bad {
        out.push(case(
            "namespace",
            &["--link", "ros2", "--ns", ns, "--headless"],
            says,
        ));
        out.push(
            case("namespace", &["--config", "c.toml", "--headless"], says).file(
                "c.toml",
                format!("[ros2]\nnamespace = {}\n", toml_string(ns)),
            ),
        );
    }
    out.push(case(
        "namespace",
        &[
            "--link",
            "ros2",
            "--ns",
            &format!("/a{ESCAPE}"),
            "--headless",
        ],
        "--ns",
    ));
    out.push(case(
        "namespace",
        &["ros2", "topics", "--ns", "/1abc", "--duration", "1"],
        "--ns",
    ));
    out.push(case(
        "namespace",
        &["--ros2", "--ns", "/a b", "--headless"],
        "--ns",
    ));
    out
}

/// Poses off the map or in walls, as `:pose`, `--kidnap`, `--start` and tour goals.
fn poses() -> Vec<Case> {
    let flat = concat!(env!("CARGO_MANIFEST_DIR"), "/maps/flat.yaml");
    let kidnap = |at: &str, world: Option<&str>, names: &str| {
        let mut args = vec!["tour", "--duration", "3", "--kidnap", at];
        if let Some(w) = world {
            args.extend(["--world", w, "--estimator", "mcl"]);
        }
        case("pose", &args, names)
    };
    let mut out = vec![
        kidnap("1@1.99,0,0", None, "--kidnap"),
        kidnap("1@-1.99,1,0", None, "the kidnap pose"),
        kidnap("1@100,100,0", None, "outside the world"),
        kidnap("1@-100,0,0", Some(flat), "outside the world"),
        kidnap("1@1e308,0,0", None, "--kidnap"),
        kidnap("1@-1e308,-1e308,0", None, "--kidnap"),
        case(
            "pose",
            &["tour", "--start", "1.99,0,0", "--duration", "1"],
            "the start",
        ),
        case(
            "pose",
            &[
                "tour",
                "--goals",
                "100,100;-100,5;1e300,0",
                "--duration",
                "20",
            ],
            "",
        )
        .or_clean(),
    ];
    for pose in ["100 100 0", "-1e300 0 0", "1e5 0 0", "0 -1e5 90"] {
        let keys = format!(":pose {pose}<enter>w");
        out.push(case("pose", &["--headless", "--keys", &keys], "").or_clean());
        out.push(
            case(
                "pose",
                &[
                    "--world",
                    flat,
                    "--estimator",
                    "mcl",
                    "--headless",
                    "--keys",
                    &keys,
                ],
                "",
            )
            .or_clean(),
        );
    }
    out
}

pub fn cases() -> Vec<Case> {
    let mut out = mcl_maps();
    out.extend(recorded_maps());
    out.extend(created_names());
    out.extend(world_outputs());
    out.extend(namespaces());
    out.extend(poses());
    out
}
