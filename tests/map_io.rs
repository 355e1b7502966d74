//! Map files as users meet them: Nav2 maps open, saved maps round-trip, saves are atomic,
//! and a bad file is refused naming the file, the field and the value.

use crate::common;

use common::scratch;
use navdeck::geometry::Point2;
use navdeck::map::grid::{FREE, OCCUPIED, OccupancyGrid, UNKNOWN};
use navdeck::map::io::{self, Extras, MapFile, SavedBlock, SavedGate, SavedLandmark};
use std::path::{Path, PathBuf};

/// A 5 x 4 grid at 5 cm with every kind of cell, and one landmark.
fn sample() -> MapFile {
    let mut grid = OccupancyGrid::new(5, 4, 0.05, Point2::new(-0.1, -0.2), FREE);
    grid.set(0, 0, OCCUPIED);
    grid.set(4, 3, UNKNOWN);
    grid.set(2, 1, OCCUPIED);
    let landmark = SavedLandmark {
        id: 301,
        category: "obstacle".into(),
        mean: [0.123456789012345, -1.0 / 3.0],
        covariance: [[1.0e-4, 2.5e-6], [2.5e-6, 3.0e-4 / 7.0]],
        sightings: 42,
    };
    MapFile {
        grid,
        extras: Some(Extras {
            version: "0.1.0".into(),
            created: "2026-11-22T06:00:00Z".into(),
            pose: Some([0.5, -0.25, 1.0]),
            landmarks: vec![landmark],
            blocks: vec![SavedBlock {
                colour: "red".into(),
                markers: [421, 422],
                position: [1.0, -0.2],
                confirmed: true,
            }],
            gates: vec![SavedGate {
                colour: "blue".into(),
                markers: [501, 502],
                center: [-2.0, 0.0],
                normal: [1.0, 0.0],
            }],
        }),
    }
}

/// The TurtleBot3 world map shared beside the checkout (or where NAVDECK_FIXTURES points).
fn turtlebot3_fixture() -> Option<PathBuf> {
    let root = std::env::var_os("NAVDECK_FIXTURES").map_or_else(
        || Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/fixtures"),
        PathBuf::from,
    );
    let path = root.join("maps/turtlebot3_world.yaml");
    path.exists().then_some(path)
}

#[test]
fn the_turtlebot3_nav2_map_opens_and_plans() {
    let Some(fixture) = turtlebot3_fixture() else {
        // A checkout without the shared fixtures (set NAVDECK_FIXTURES to point at them).
        eprintln!("skipped: the TurtleBot3 fixture is not beside this checkout");
        return;
    };
    let map = io::load(&fixture).unwrap_or_else(|e| panic!("{}: {e}", fixture.display()));
    let g = &map.grid;
    assert_eq!((g.width, g.height), (384, 384));
    assert_eq!(g.resolution, 0.05);
    assert_eq!(g.origin, Point2::new(-10.0, -10.0));
    // Cells read off the image: a wall, open floor, and unexplored space outside.
    assert_eq!(g.at(Point2::new(1.275, 0.075)), OCCUPIED);
    assert_eq!(g.at(Point2::new(2.275, 0.025)), FREE);
    assert_eq!(g.at(Point2::new(-9.99, -9.99)), UNKNOWN);
    let counts = |v| g.cells.iter().filter(|&&c| c == v).count();
    assert_eq!((counts(OCCUPIED), counts(FREE)), (795, 7939));
    assert!(map.extras.is_none());
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_navdeck"))
        .args([
            "plan",
            "--map",
            fixture.to_str().unwrap(),
            "--from",
            "-2,-0.5",
            "--to",
            "2,0.5",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn save_then_load_gives_the_same_grid_and_landmarks() {
    let dir = scratch("round");
    let path = dir.join("lab.yaml");
    let map = sample();
    io::save(&path, &map).unwrap();
    assert!(dir.join("lab.pgm").exists());
    let back = io::load(&path).unwrap();
    assert_eq!(back.grid, map.grid);
    let (a, b) = (map.extras.unwrap(), back.extras.unwrap());
    assert_eq!(a.landmarks.len(), b.landmarks.len());
    for (x, y) in a.landmarks.iter().zip(&b.landmarks) {
        for i in 0..2 {
            assert!((x.mean[i] - y.mean[i]).abs() < 1e-9);
            for j in 0..2 {
                assert!((x.covariance[i][j] - y.covariance[i][j]).abs() < 1e-9);
            }
        }
        assert_eq!((x.id, x.sightings), (y.id, y.sightings));
    }
    assert_eq!(a.pose, b.pose);
    assert_eq!((a.blocks, a.gates), (b.blocks, b.gates));
    // The YAML is map_server's, with navdeck's part under its own key.
    let text = std::fs::read_to_string(&path).unwrap();
    for key in [
        "image: lab.pgm",
        "resolution: 0.05",
        "mode: trinary",
        "navdeck:",
    ] {
        assert!(text.contains(key), "{key} in\n{text}");
    }
}

#[test]
fn a_save_that_fails_half_way_leaves_the_old_map_whole() {
    let dir = scratch("atomic");
    let path = dir.join("lab.yaml");
    io::save(&path, &sample()).unwrap();
    let before_yaml = std::fs::read(&path).unwrap();
    let before_pgm = std::fs::read(dir.join("lab.pgm")).unwrap();
    let mut newer = sample();
    newer.grid.set(1, 1, OCCUPIED);
    // The disk fills up half-way through the image.
    let mut failing = |p: &Path, bytes: &[u8]| -> std::io::Result<()> {
        std::fs::write(p, &bytes[..bytes.len() / 2])?;
        Err(std::io::Error::other("no space left on device"))
    };
    let err = io::save_with(&path, &newer, &mut failing).unwrap_err();
    assert!(err.to_string().contains("lab.pgm") && err.to_string().contains("no space"));
    assert_eq!(std::fs::read(&path).unwrap(), before_yaml);
    assert_eq!(std::fs::read(dir.join("lab.pgm")).unwrap(), before_pgm);
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| n.ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
    // A save that completes keeps the previous version as .bak.
    io::save(&path, &newer).unwrap();
    assert_eq!(
        std::fs::read(dir.join("lab.yaml.bak")).unwrap(),
        before_yaml
    );
    assert_eq!(io::load(&path).unwrap().grid, newer.grid);
}

/// Writes a YAML (and a PGM) and returns the load error's text.
fn refusal(name: &str, yaml: &str, pgm: &[u8]) -> String {
    let dir = scratch(name);
    std::fs::write(dir.join("m.pgm"), pgm).unwrap();
    let path = dir.join("m.yaml");
    std::fs::write(&path, yaml).unwrap();
    let err = io::load(&path).unwrap_err().to_string();
    assert!(
        err.contains("m.yaml") || err.contains("m.pgm"),
        "names the file: {err}"
    );
    err
}

const IMAGE: &[u8] = b"P5 2 2 255\n\xfe\x00\xcd\xfe";

fn yaml(body: &str) -> String {
    format!("image: m.pgm\n{body}")
}

#[test]
fn bad_map_files_are_refused_naming_field_and_value() {
    let ok = "resolution: 0.05\norigin: [0, 0, 0]\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
    assert!(
        refusal(
            "missing",
            &yaml("origin: [0, 0, 0]\noccupied_thresh: 0.65\nfree_thresh: 0.2\n"),
            IMAGE
        )
        .contains("resolution")
    );
    assert!(refusal("type", &yaml(&ok.replace("0.05", "fine")), IMAGE).contains("resolution"));
    let e = refusal("negative", &yaml(&ok.replace("0.05", "-0.05")), IMAGE);
    assert!(e.contains("`resolution` = -0.05"), "{e}");
    let e = refusal(
        "nan",
        &yaml(&ok.replace("[0, 0, 0]", "[.nan, 0, 0]")),
        IMAGE,
    );
    assert!(e.contains("`origin`") && e.contains("NaN"), "{e}");
    let e = refusal("order", &yaml(&ok.replace("0.196", "0.7")), IMAGE);
    assert!(e.contains("`free_thresh` = 0.7"), "{e}");
    let e = refusal("mode", &yaml(&format!("{ok}mode: fancy\n")), IMAGE);
    assert!(e.contains("`mode` = fancy"), "{e}");
    let e = refusal("short", &yaml(ok), b"P5 3 3 255\n\x00\x00");
    assert!(e.contains("truncated") && e.contains("9 values"), "{e}");
    let e = refusal("maxval", &yaml(ok), b"P5 1 1 99999\n\x00\x00");
    assert!(e.contains("maxval") && e.contains("99999"), "{e}");
    let e = refusal("huge", &yaml(ok), b"P5 4000000 4000000 255\n");
    assert!(e.contains("width") && e.contains("4000000"), "{e}");
}

#[test]
fn map_server_modes_negate_plain_pgm_and_absolute_images_are_read() {
    let dir = scratch("modes");
    // Pixels 0 (black), 128 (grey), 255 (white), plain P2.
    std::fs::write(dir.join("g.pgm"), "P2\n3 1\n255\n0 128 255\n").unwrap();
    let image = dir.join("g.pgm");
    let read = |mode: &str, negate: u8| {
        let path = dir.join(format!("{mode}{negate}.yaml"));
        std::fs::write(
            &path,
            format!(
                "image: {}\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: {negate}\noccupied_thresh: 0.65\nfree_thresh: 0.196\nmode: {mode}\n",
                image.display()
            ),
        )
        .unwrap();
        io::load(&path).unwrap().grid.cells
    };
    assert_eq!(read("trinary", 0), [OCCUPIED, UNKNOWN, FREE]);
    assert_eq!(read("trinary", 1), [FREE, UNKNOWN, OCCUPIED]);
    let scaled = read("scale", 0);
    assert_eq!((scaled[0], scaled[2]), (OCCUPIED, FREE));
    assert!((1..100).contains(&scaled[1]), "{scaled:?}");
    assert_eq!(read("raw", 0), [0, UNKNOWN, UNKNOWN]);
}

#[test]
fn the_console_saves_its_map_by_key_command_and_autosave() {
    use navdeck::app::KeyKind;
    use navdeck::keymap::parse_key_sequence;
    let dir = scratch("console");
    let mut app = navdeck::session::Session::load(&navdeck::session::SessionSpec {
        world: None,
        seed: 1,
        start: None,
        config: None,
        keymap: None,
        link: navdeck::session::LinkChoice::Sim,
        localize: Default::default(),
    })
    .unwrap()
    .into_app(0.0);
    app.set_maps_dir(dir.clone());
    let keys = parse_key_sequence("wwwwwwwwwwS:save lab-1<enter>:save ../up<enter>").unwrap();
    navdeck::runners::headless::run(&mut app, &keys, 10.0);
    for name in ["saved", "lab-1"] {
        let map = io::load(&dir.join(format!("{name}.yaml"))).unwrap();
        let extras = map.extras.unwrap();
        assert!(
            extras.landmarks.len() >= 5,
            "{name}: {}",
            extras.landmarks.len()
        );
        assert!(extras.pose.is_some());
        assert!(
            !extras.blocks.is_empty(),
            "{name}: the blocks seen on the way"
        );
        assert!(map.grid.cells.contains(&OCCUPIED), "the lidar's walls");
        assert!(map.grid.cells.contains(&FREE));
    }
    let said: Vec<String> = app.log_book().iter().map(|e| e.text.clone()).collect();
    assert!(said.iter().any(|l| l.contains("name `../up`")), "{said:?}");
    assert!(!dir.join("../up.yaml").exists());
    // Exploring saves the arena's autosave every 30 s.
    let t = app.now();
    app.handle_key("e".parse().unwrap(), KeyKind::Press, t);
    for k in 1..=320 {
        app.update(t + 0.1 * f64::from(k));
    }
    assert!(io::load(&dir.join("autosave-arena.yaml")).is_ok());
}

#[test]
fn load_mode_picks_a_saved_map_and_seeds_the_filter_with_its_landmarks() {
    use navdeck::keymap::parse_key_sequence;
    let spec = navdeck::session::SessionSpec {
        world: None,
        seed: 1,
        start: None,
        config: None,
        keymap: None,
        link: navdeck::session::LinkChoice::Sim,
        localize: Default::default(),
    };
    let dir = scratch("load");
    let mut first = navdeck::session::Session::load(&spec)
        .unwrap()
        .into_app(0.0);
    first.set_maps_dir(dir.clone());
    let drive = ("w".repeat(20) + &"a".repeat(9)).repeat(4);
    navdeck::runners::headless::run(
        &mut first,
        &parse_key_sequence(&format!("{drive}:save arena<enter>")).unwrap(),
        10.0,
    );
    let saved = first.pilot().slam().landmark_count();
    assert!(saved >= 10, "{saved}");
    // An unreadable file beside it is listed but does not load.
    std::fs::write(
        dir.join("broken.yaml"),
        "image: broken.pgm\nresolution: 0\n",
    )
    .unwrap();

    let mut second = navdeck::session::Session::load(&spec)
        .unwrap()
        .into_app(0.0);
    second.set_maps_dir(dir.clone());
    navdeck::runners::headless::run(
        &mut second,
        &parse_key_sequence("l<down><enter>").unwrap(),
        10.0,
    );
    let said: Vec<String> = second.log_book().iter().map(|e| e.text.clone()).collect();
    assert!(
        said.iter().any(|l| l.starts_with("load: 2 maps")),
        "{said:?}"
    );
    assert!(
        said.iter()
            .any(|l| l.contains("map not loaded, the current one stays")),
        "{said:?}"
    );
    assert_eq!(second.pilot().mode(), navdeck::app::mode::Mode::Load);
    navdeck::runners::headless::run(
        &mut second,
        &parse_key_sequence("<up><enter>").unwrap(),
        10.0,
    );
    assert_eq!(
        second.pilot().mode(),
        navdeck::app::mode::Mode::Manual,
        "{:?}",
        second
            .log_book()
            .iter()
            .map(|e| e.text.clone())
            .collect::<Vec<_>>()
    );
    assert!(
        second.pilot().slam().landmark_count() >= saved,
        "the saved landmarks are the prior"
    );
    assert!(
        second
            .log_book()
            .iter()
            .any(|e| e.text.contains("loaded") && e.text.contains("arena.yaml"))
    );
    // Markers the robot cannot see from its start are already on its map.
    let far = first.pilot().slam().landmarks().map(|l| l.id).find(|id| {
        second.pilot().slam().landmark(*id).is_some()
            && !matches!(id, 4..=6 | 310 | 311 | 521 | 522)
    });
    assert!(far.is_some());
}

#[test]
fn mangled_map_files_are_refused_never_crash() {
    use rand::{Rng, SeedableRng};
    let yaml = "image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\nmode: trinary\nnavdeck:\n  version: x\n  landmarks: []\n";
    let image = b"P5\n# c\n4 3\n255\n\xfe\x00\xcd\xfe\xfe\x00\xcd\xfe\xfe\x00\xcd\xfe".to_vec();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(6);
    let mut refused = 0;
    for _ in 0..3000 {
        let mut y = yaml.as_bytes().to_vec();
        let mut p = image.clone();
        for _ in 0..rng.random_range(1..4) {
            let target = if rng.random_bool(0.5) { &mut y } else { &mut p };
            let at = rng.random_range(0..target.len());
            match rng.random_range(0..4) {
                0 => target[at] = rng.random(),
                1 => target.insert(at, rng.random()),
                2 => {
                    target.remove(at);
                }
                _ => target.truncate(at),
            }
            if target.is_empty() {
                target.push(b'P');
            }
        }
        let text = String::from_utf8_lossy(&y);
        let result = io::decode(&text, Path::new("m.yaml"), &mut |_| Ok(p.clone()));
        if let Err(e) = result {
            refused += 1;
            // Every refusal names the file: the YAML, or the image it (now) names.
            let said = e.to_string();
            assert!(
                said.contains("m.yaml") || said.starts_with("map image"),
                "{said}"
            );
        }
    }
    assert!(refused > 1000, "most mangled files are refused: {refused}");
}

#[test]
fn a_tiny_plain_pgm_cannot_make_the_reader_reserve_gigabytes() {
    let e = io::decode(
        "image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\noccupied_thresh: 0.65\nfree_thresh: 0.196\n",
        Path::new("m.yaml"),
        &mut |_| Ok(b"P2 8000 8000 255\n1 2 3".to_vec()),
    )
    .unwrap_err();
    assert!(e.to_string().contains("truncated"), "{e}");
}

/// A symbolic link planted at the save's temporary name makes the save fail with a
/// message; the link's target is never written.
#[test]
fn a_save_never_writes_through_a_planted_link() {
    let dir = scratch("planted-link");
    let target = dir.join("elsewhere.txt");
    std::fs::write(&target, "keep me").unwrap();
    let path = dir.join("saved.yaml");
    std::os::unix::fs::symlink(&target, dir.join("saved.yaml.tmp")).unwrap();
    let err = io::save(&path, &sample()).unwrap_err().to_string();
    assert!(err.contains("saved.yaml.tmp"), "{err}");
    assert_eq!(std::fs::read_to_string(&target).unwrap(), "keep me");
    // A file an interrupted save left behind is no obstacle.
    let dir = scratch("stale-tmp");
    let path = dir.join("saved.yaml");
    std::fs::write(dir.join("saved.yaml.tmp"), "half a save").unwrap();
    io::save(&path, &sample()).unwrap();
    assert!(io::load(&path).is_ok());
}

/// Hostile headers: a map nested ever deeper, a resolution of 1e308, a device as the
/// image; each refused at once, naming what is wrong.
#[test]
fn hostile_map_headers_are_refused_quickly() {
    let dir = scratch("hostile-headers");
    let deep = format!(
        "image: m.pgm\nresolution: {}0.05{}\n",
        "[".repeat(5000),
        "]".repeat(5000)
    );
    std::fs::write(dir.join("deep.yaml"), deep).unwrap();
    let err = io::load(&dir.join("deep.yaml")).unwrap_err().to_string();
    assert!(err.contains("nested"), "{err}");
    let huge = "image: m.pgm\nresolution: 1e308\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
    std::fs::write(dir.join("huge.yaml"), huge).unwrap();
    let err = io::load(&dir.join("huge.yaml")).unwrap_err().to_string();
    assert!(err.contains("resolution") && err.contains("1e308"), "{err}");
    let device = "image: /dev/zero\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
    std::fs::write(dir.join("device.yaml"), device).unwrap();
    let err = io::load(&dir.join("device.yaml")).unwrap_err().to_string();
    assert!(err.contains("not a regular file"), "{err}");
}

#[test]
fn a_file_that_is_not_a_map_is_refused_without_showing_what_it_holds() {
    let dir = scratch("not-a-map");
    let path = dir.join("passwd");
    std::fs::write(&path, "root:x:0:0:root:/root:/bin/bash\n").unwrap();
    let e = io::load(&path).unwrap_err().to_string();
    assert!(e.contains("not a map YAML"), "{e}");
    assert!(!e.contains("root:x"), "{e}");
    std::fs::write(&path, "image: [\"secret text\", 2]\n").unwrap();
    let e = io::load(&path).unwrap_err().to_string();
    assert!(!e.contains("secret"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_refused_save_leaves_no_temporary_file() {
    let dir = scratch("refused-save");
    let path = dir.join("lab.yaml");
    // A link planted at the YAML's temporary name: the image is written first.
    std::os::unix::fs::symlink(dir.join("elsewhere"), dir.join("lab.yaml.tmp")).unwrap();
    let e = io::save(&path, &sample()).unwrap_err().to_string();
    assert!(e.contains("lab.yaml"), "{e}");
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    assert!(left.is_empty(), "{left:?}");
    assert!(!dir.join("elsewhere").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
