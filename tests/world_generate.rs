//! Generated worlds: every seed and style gives a world that loads back from its file, has
//! what was asked for, and lets the robot reach every block and gate; the same seed gives
//! the same file; the command line writes files the other commands load, and refuses bad
//! options by name.

use crate::common;

use common::{navdeck, scratch};

use navdeck::geometry::Point2;
use navdeck::perception::markers::MarkerCategory;
use navdeck::sim::World;
use navdeck::sim::generate::{GenerateOptions, Style, check_reachable, generate};
use std::collections::HashSet;
use std::path::Path;

const SEEDS: u64 = 200;

fn options(seed: u64, style: Style) -> GenerateOptions {
    GenerateOptions {
        seed,
        style,
        ..GenerateOptions::default()
    }
}

/// Everything a world must hold, whatever the seed.
fn assert_sound(world: &World, o: &GenerateOptions) {
    let name = o.name();
    let back = World::from_toml(&world.to_toml(), Path::new(&name))
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(
        back.to_toml(),
        world.to_toml(),
        "{name}: the file reads back"
    );
    assert_eq!(world.name, name);
    assert_eq!(world.blocks.len(), o.blocks, "{name}");
    assert_eq!(world.obstacles.len(), o.obstacles, "{name}");
    for colour in ["red", "blue"] {
        assert_eq!(
            world
                .gates
                .iter()
                .filter(|g| g.color.label() == colour)
                .count(),
            1,
            "{name}: one {colour} gate"
        );
    }
    let mut ids = HashSet::new();
    let block_ids = world.blocks.iter().flat_map(|b| b.markers);
    for id in world.markers.iter().map(|m| m.id).chain(block_ids) {
        assert!(ids.insert(id), "{name}: marker {id} twice");
        assert_ne!(
            MarkerCategory::of(id),
            MarkerCategory::Unknown,
            "{name}: {id}"
        );
    }
    for g in &world.gates {
        assert_eq!(
            g.markers[0] % 2,
            1,
            "{name}: gate ids pair odd with the next"
        );
        assert_eq!(g.markers[1], g.markers[0] + 1, "{name}");
    }
    let (w, h) = o.size();
    assert_eq!((world.width, world.height), (w, h), "{name}");
    // Blocks stand in open floor, the start is clear of every wall and box.
    let clearance = |p: Point2| {
        let inside = world.obstacles.iter().any(|b| {
            let (s, c) = b.pose.theta.sin_cos();
            let (dx, dy) = (p.x - b.pose.x, p.y - b.pose.y);
            (c * dx + s * dy).abs() <= b.width / 2.0 && (-s * dx + c * dy).abs() <= b.height / 2.0
        });
        let nearest = world
            .walls
            .iter()
            .map(|s| s.distance_to(p))
            .fold(f64::INFINITY, f64::min);
        if inside { 0.0 } else { nearest }
    };
    for b in &world.blocks {
        let c = clearance(b.pose.position());
        assert!(
            c >= 0.5 - 1e-9,
            "{name}: block {} {c:.3} m from a wall",
            b.markers[0]
        );
    }
    let c = clearance(world.start.position());
    assert!(c >= 0.4 - 1e-9, "{name}: the start is {c:.3} m from a wall");
    check_reachable(world).unwrap_or_else(|e| panic!("{name}: {e}"));
}

#[test]
fn every_seed_and_style_gives_a_sound_world() {
    for style in Style::ALL {
        for seed in 1..=SEEDS {
            let o = options(seed, style);
            let world = generate(&o).unwrap_or_else(|e| panic!("{e}"));
            assert_sound(&world, &o);
        }
    }
}

#[test]
fn both_colours_appear_from_two_blocks() {
    let o = GenerateOptions {
        blocks: 2,
        obstacles: 0,
        ..options(5, Style::Boxes)
    };
    let world = generate(&o).unwrap();
    assert_sound(&world, &o);
    let colours: HashSet<_> = world.blocks.iter().map(|b| b.color).collect();
    assert_eq!(colours.len(), 2);
}

#[test]
fn larger_worlds_hold_more() {
    for (style, size, blocks, obstacles) in [
        (Style::Boxes, (8.0, 6.0), 8, 6),
        (Style::Rooms, (10.0, 8.0), 10, 5),
        (Style::Corridors, (12.0, 6.0), 6, 4),
        (Style::Corridors, (3.0, 6.0), 2, 1),
        (Style::Loop, (12.0, 6.0), 8, 4),
        (Style::Loop, (5.0, 9.0), 4, 2),
    ] {
        for seed in 1..=10 {
            let o = GenerateOptions {
                seed,
                size: Some(size),
                blocks,
                obstacles,
                style,
                ..GenerateOptions::default()
            };
            let world = generate(&o).unwrap_or_else(|e| panic!("{size:?}: {e}"));
            assert_sound(&world, &o);
        }
    }
}

#[test]
fn the_same_seed_gives_the_same_file_and_another_seed_another() {
    for style in Style::ALL {
        let a = generate(&options(7, style)).unwrap().to_toml();
        let b = generate(&options(7, style)).unwrap().to_toml();
        let c = generate(&options(8, style)).unwrap().to_toml();
        assert_eq!(a, b, "{style}");
        assert_ne!(a, c, "{style}");
    }
}

#[test]
fn impossible_options_are_refused_by_name() {
    let small = GenerateOptions {
        size: Some((1.5, 1.5)),
        ..GenerateOptions::default()
    };
    let e = generate(&small).unwrap_err().to_string();
    assert!(e.contains("`size`") && e.contains("1.5,1.5"), "{e}");
    let crowded = GenerateOptions {
        size: Some((2.0, 2.0)),
        blocks: 8,
        ..GenerateOptions::default()
    };
    let e = generate(&crowded).unwrap_err().to_string();
    assert!(e.contains("`size`") && e.contains("8 blocks"), "{e}");
    let many = GenerateOptions {
        blocks: 31,
        ..GenerateOptions::default()
    };
    assert!(
        generate(&many)
            .unwrap_err()
            .to_string()
            .contains("`blocks` = 31")
    );
    let nan = GenerateOptions {
        size: Some((f64::NAN, 4.0)),
        ..GenerateOptions::default()
    };
    assert!(generate(&nan).unwrap_err().to_string().contains("`size`"));
    assert!("mazes".parse::<Style>().unwrap_err().contains("mazes"));
}

#[test]
fn world_generate_writes_a_file_the_twin_and_the_mission_load() {
    let dir = scratch("generate");
    let file = dir.join("rooms-7.toml");
    let path = file.to_str().unwrap();
    let out = navdeck(&[
        "world", "generate", "--seed", "7", "--style", "rooms", "-o", path,
    ]);
    let said = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(said.lines().count(), 1, "{said}");
    assert!(
        said.contains(path) && said.contains("generated:rooms:7"),
        "{said}"
    );
    assert!(
        said.contains("3 blocks") && said.contains("red and blue"),
        "{said}"
    );
    let world = World::load(&file).unwrap();
    assert_eq!(world, generate(&options(7, Style::Rooms)).unwrap());

    let out = navdeck(&["--headless", "--json", "--world", path, "--keys", "ww"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let out = navdeck(&["mission", "--world", path, "--time-limit", "5", "--json"]);
    let report: serde_json::Value = serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(&out.stderr)));
    assert_eq!(report["world"], "generated:rooms:7");
    assert_eq!(report["total"], 3);

    // The mission on a generated world without a file names it by style and seed.
    let out = navdeck(&[
        "mission",
        "--generated",
        "--style",
        "corridors",
        "--seed",
        "4",
        "--time-limit",
        "5",
        "--json",
    ]);
    let report: serde_json::Value = serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(&out.stderr)));
    assert_eq!(report["world"], "generated:corridors:4");
    assert_eq!(report["seed"], 4);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn bad_options_are_refused_naming_the_flag() {
    let dir = scratch("bad-options");
    let file = dir.join("bad.toml");
    for (args, flag, value) in [
        (vec!["--size", "4x4"], "--size", "4x4"),
        (vec!["--size", "1,1"], "--size", "1,1"),
        (vec!["--size", "2,2", "--blocks", "9"], "--size", "2,2"),
        (vec!["--blocks", "many"], "--blocks", "many"),
        (vec!["--blocks", "40"], "--blocks", "40"),
        (vec!["--obstacles", "-1"], "--obstacles", "-1"),
        (vec!["--style", "maze"], "--style", "maze"),
        (vec!["--loops"], "--loops", "boxes"),
        (vec!["--style", "loop", "--loops"], "--loops", "loop"),
    ] {
        refused(&args, flag, value, &file);
    }
    for flag in ["--style", "--no-wall-markers", "--loops"] {
        let mut args = vec!["mission", flag];
        if flag == "--style" {
            args.push("rooms");
        }
        let out = navdeck(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains(flag) && err.contains("--generated"), "{err}");
    }
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn world_generate_replaces_a_planted_link_and_keeps_the_old_file_as_bak() {
    let dir = scratch("generate-links");
    let victim = dir.join("victim");
    std::fs::write(&victim, "keep").unwrap();
    let out = dir.join("w.toml");
    std::os::unix::fs::symlink(&victim, &out).unwrap();
    let run = |path: &std::path::Path| {
        navdeck(&[
            "world",
            "generate",
            "--seed",
            "3",
            "-o",
            path.to_str().unwrap(),
        ])
    };
    let said = run(&out);
    assert!(said.status.success(), "{said:?}");
    // The link was moved aside, not written through.
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "keep");
    assert!(
        std::fs::symlink_metadata(dir.join("w.toml.bak"))
            .unwrap()
            .is_symlink()
    );
    let first = std::fs::read_to_string(&out).unwrap();
    assert!(first.contains("[[walls]]"), "{first}");
    assert!(String::from_utf8_lossy(&said.stdout).contains("w.toml.bak"));
    // Again: the file it replaces is kept.
    assert!(run(&out).status.success());
    assert_eq!(
        std::fs::read_to_string(dir.join("w.toml.bak")).unwrap(),
        first
    );
    // A dangling link: nothing is created where it points.
    let dangling = dir.join("d.toml");
    std::os::unix::fs::symlink(dir.join("made-through-link"), &dangling).unwrap();
    assert!(run(&dangling).status.success());
    assert!(!dir.join("made-through-link").exists());
    // A link planted at the temporary name: refused, nothing left behind.
    let guarded = dir.join("g.toml");
    std::os::unix::fs::symlink(&victim, dir.join("g.toml.tmp")).unwrap();
    let said = run(&guarded);
    assert_eq!(said.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&said.stderr).contains("not writing through it"));
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "keep");
    assert!(!guarded.exists() && !dir.join("g.toml.tmp").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn worlds_without_wall_markers_and_with_loops_are_written_and_run_by_name() {
    let dir = scratch("generate-bare");
    let file = dir.join("rooms-7-bare.toml");
    let path = file.to_str().unwrap();
    let out = navdeck(&[
        "world",
        "generate",
        "--seed",
        "7",
        "--style",
        "rooms",
        "--size",
        "8,6",
        "--loops",
        "--no-wall-markers",
        "-o",
        path,
    ]);
    let said = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(said.contains("generated:rooms:7:loops:bare"), "{said}");
    assert!(said.contains(" 0 wall and box markers"), "{said}");
    let world = World::load(&file).unwrap();
    let text = std::fs::read_to_string(&file).unwrap();
    assert!(text.starts_with("# navdeck world generate --seed 7 --style rooms --size 8,6"));
    assert!(
        text.lines()
            .next()
            .unwrap()
            .ends_with("--loops --no-wall-markers"),
        "{text}"
    );
    // Only the gates' four markers are fixed in the world; the blocks carry theirs.
    assert_eq!(world.markers.len(), 4);
    let marked = GenerateOptions {
        size: Some((8.0, 6.0)),
        loops: true,
        ..options(7, Style::Rooms)
    };
    assert_eq!(
        world.walls,
        generate(&marked).unwrap().walls,
        "the same layout"
    );

    // A loop: its length round the centreline is said.
    let ring = dir.join("loop.toml");
    let out = navdeck(&[
        "world",
        "generate",
        "--seed",
        "2",
        "--style",
        "loop",
        "--size",
        "12,6",
        "-o",
        ring.to_str().unwrap(),
    ]);
    let said = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let length: f64 = said
        .split("a corridor ")
        .nth(1)
        .and_then(|rest| rest.split(" m round").next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{said}"));
    assert!(length >= 30.0, "{said}");

    // The mission takes the same flags on a generated world and names it so.
    let out = navdeck(&[
        "mission",
        "--generated",
        "--style",
        "corridors",
        "--size",
        "7,5",
        "--loops",
        "--no-wall-markers",
        "--seed",
        "4",
        "--time-limit",
        "5",
        "--json",
    ]);
    let report: serde_json::Value = serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(&out.stderr)));
    assert_eq!(report["world"], "generated:corridors:4:loops:bare");
    std::fs::remove_dir_all(dir).unwrap();
}

/// Boundary markers along the south wall (y = -h/2), sorted by x.
fn south_markers(world: &World) -> Vec<f64> {
    let mut xs: Vec<f64> = (world.markers.iter())
        .filter(|m| MarkerCategory::of(m.id) == MarkerCategory::Boundary)
        .filter(|m| (m.position.y + world.height / 2.0).abs() < 1e-9)
        .map(|m| m.position.x)
        .collect();
    xs.sort_by(f64::total_cmp);
    xs
}

/// The gaps between the collinear pieces of the interior walls: the doorways' widths.
fn doorways(world: &World) -> Vec<f64> {
    let interior = world.walls.len() - 4 - 4 * world.obstacles.len();
    let walls = &world.walls[4..4 + interior];
    // Each piece's gap to the next piece on its line; pieces of two walls that meet end
    // to end leave none.
    (walls.iter())
        .filter_map(|a| {
            (walls.iter())
                .filter_map(|b| {
                    let along_y = (a.a.x - a.b.x).abs() < 1e-9 && (b.a.x - b.b.x).abs() < 1e-9;
                    let along_x = (a.a.y - a.b.y).abs() < 1e-9 && (b.a.y - b.b.y).abs() < 1e-9;
                    let gap = if along_y && (a.a.x - b.a.x).abs() < 1e-9 {
                        b.a.y - a.b.y
                    } else if along_x && (a.a.y - b.a.y).abs() < 1e-9 {
                        b.a.x - a.b.x
                    } else {
                        return None;
                    };
                    (gap > -1e-9).then_some(gap)
                })
                .fold(None, |m: Option<f64>, g| Some(m.map_or(g, |m| m.min(g))))
        })
        .filter(|g| *g > 1e-9)
        .collect()
}

#[test]
fn marker_spacing_colours_doorways_and_rooms_give_what_was_asked() {
    use navdeck::sim::BlockColor;
    use navdeck::sim::generate::Colours;
    for seed in 1..=8 {
        // Markers every 1 m along the walls.
        let sparse = GenerateOptions {
            marker_spacing: 1.0,
            ..options(seed, Style::Boxes)
        };
        let world = generate(&sparse).unwrap_or_else(|e| panic!("{e}"));
        assert_sound(&world, &sparse);
        let xs = south_markers(&world);
        assert!(
            xs.windows(2).all(|w| (w[1] - w[0] - 1.0).abs() < 1e-6),
            "{xs:?}"
        );

        // Colours drawn at random: the same for the same seed, at most a gate's drop
        // places of either, and all red with `one`.
        let random = GenerateOptions {
            blocks: 12,
            colours: Colours::Random,
            size: Some((6.0, 6.0)),
            ..options(seed, Style::Boxes)
        };
        let world = generate(&random).unwrap_or_else(|e| panic!("{e}"));
        assert_sound(&world, &random);
        let reds = world
            .blocks
            .iter()
            .filter(|b| b.color == BlockColor::Red)
            .count();
        assert!(reds <= 9 && 12 - reds <= 9, "{reds} red of 12");
        assert_eq!(generate(&random).unwrap().to_toml(), world.to_toml());
        let one = GenerateOptions {
            blocks: 8,
            colours: Colours::One,
            ..options(seed, Style::Boxes)
        };
        let world = generate(&one).unwrap_or_else(|e| panic!("{e}"));
        assert_sound(&world, &one);
        assert!(world.blocks.iter().all(|b| b.color == BlockColor::Red));

        // Six rooms in an 8 m x 6 m flat, every doorway 0.7 m.
        let flat = GenerateOptions {
            size: Some((8.0, 6.0)),
            rooms: Some(6),
            doorway: Some(0.7),
            ..options(seed, Style::Rooms)
        };
        let world = generate(&flat).unwrap_or_else(|e| panic!("{e}"));
        assert_sound(&world, &flat);
        let gaps = doorways(&world);
        assert_eq!(gaps.len(), 5, "five walls between six rooms: {gaps:?}");
        assert!(gaps.iter().all(|g| (g - 0.7).abs() < 1e-6), "{gaps:?}");
    }
    // A 12 m flat with many rooms and sparse markers.
    let large = GenerateOptions {
        size: Some((12.0, 10.0)),
        rooms: Some(9),
        marker_spacing: 1.2,
        blocks: 8,
        ..options(3, Style::Rooms)
    };
    let world = generate(&large).unwrap_or_else(|e| panic!("{e}"));
    assert_sound(&world, &large);
    assert_eq!(doorways(&world).len(), 8);
}

#[test]
fn every_variant_has_its_own_name_and_its_command_remakes_it() {
    use navdeck::sim::generate::Colours;
    let base = GenerateOptions {
        size: Some((8.0, 6.0)),
        ..options(4, Style::Rooms)
    };
    let variants = [
        base.clone(),
        GenerateOptions {
            marker_spacing: 0.8,
            ..base.clone()
        },
        GenerateOptions {
            colours: Colours::Random,
            ..base.clone()
        },
        GenerateOptions {
            colours: Colours::One,
            ..base.clone()
        },
        GenerateOptions {
            doorway: Some(0.9),
            ..base.clone()
        },
        GenerateOptions {
            rooms: Some(5),
            ..base.clone()
        },
    ];
    let names: HashSet<String> = variants.iter().map(GenerateOptions::name).collect();
    assert_eq!(names.len(), variants.len(), "{names:?}");
    assert_eq!(variants[1].name(), "generated:rooms:4:markers0.8");
    let dir = scratch("generate-variants");
    for o in &variants[1..] {
        let file = dir.join("v.toml");
        let command = o.command();
        let mut args: Vec<&str> = command.split(' ').skip(1).collect();
        args.extend(["-o", file.to_str().unwrap()]);
        let out = navdeck(&args);
        assert!(
            out.status.success(),
            "{command}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let world = World::load(&file).unwrap();
        assert_eq!(world.to_toml(), generate(o).unwrap().to_toml(), "{command}");
        assert_eq!(world.name, o.name());
    }
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn the_new_options_are_refused_naming_the_flag_and_value() {
    let dir = scratch("bad-new-options");
    let file = dir.join("bad.toml");
    for (args, flag, value) in [
        (vec!["--marker-spacing", "0.2"], "--marker-spacing", "0.2"),
        (vec!["--marker-spacing", "wide"], "--marker-spacing", "wide"),
        (vec!["--colours", "purple"], "--colours", "purple"),
        (vec!["--colours", "one", "--blocks", "10"], "--blocks", "10"),
        (vec!["--blocks", "19"], "--blocks", "19"),
        (vec!["--doorway", "0.9"], "--doorway", "0.9 with boxes"),
        (
            vec!["--style", "rooms", "--doorway", "0.3"],
            "--doorway",
            "0.3",
        ),
        (vec!["--style", "rooms", "--rooms", "1"], "--rooms", "1"),
        (vec!["--style", "rooms", "--rooms", "40"], "--rooms", "40"),
        (
            vec!["--style", "corridors", "--rooms", "3"],
            "--rooms",
            "3 with corridors",
        ),
    ] {
        let err = refused(&args, flag, value, &file);
        let first = err.lines().next().unwrap_or_default();
        assert!(
            first.contains(flag) && first.contains(value),
            "one line says it: {err}"
        );
    }
    std::fs::remove_dir_all(dir).unwrap();
}

/// `navdeck world generate --seed 1 -o FILE ARGS` is refused with usage status 2, naming
/// `flag` and `value`, without a panic and without writing FILE; returns what it said.
fn refused(args: &[&str], flag: &str, value: &str, file: &std::path::Path) -> String {
    let path = file.to_str().unwrap();
    let mut all = vec!["world", "generate", "--seed", "1", "-o", path];
    all.extend(args.iter().copied());
    let out = navdeck(&all);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(err.contains(flag) && err.contains(value), "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(!file.exists(), "{args:?} wrote a file");
    err
}
