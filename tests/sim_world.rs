//! World files: the shipped ones load, and every kind of bad file is refused with a message
//! naming the file, the field and the value (and the line where there is one).

use navdeck::geometry::Point2;
use navdeck::map::grid::{FREE, OCCUPIED};
use navdeck::perception::markers::MarkerCategory;
use navdeck::sim::{BlockColor, World, WorldError};
use std::collections::HashSet;
use std::path::Path;

const HEADER: &str = "name = \"t\"\nsize = [4.0, 4.0]\nstart = [0.0, 0.0, 0.0]\n\
[[walls]]\npoints = [[-2.0, -2.0], [2.0, -2.0], [2.0, 2.0], [-2.0, 2.0]]\nclosed = true\n\
markers = { first_id = 1, spacing = 0.5 }\n";

fn refuse(extra: &str) -> String {
    let text = format!("{HEADER}{extra}");
    match World::from_toml(&text, Path::new("maps/bad.toml")) {
        Ok(_) => panic!("accepted a bad world:\n{extra}"),
        Err(e) => {
            let msg = e.to_string();
            assert!(msg.contains("maps/bad.toml"), "no file name in: {msg}");
            msg
        }
    }
}

fn manifest(path: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

#[test]
fn default_arena_is_seed_001s_arena() {
    let w = World::default_arena();
    assert_eq!((w.width, w.height), (4.0, 4.0));
    // Boundary every 0.5 m on four 4 m walls, facing inward.
    let boundary: Vec<_> = w
        .markers
        .iter()
        .filter(|m| MarkerCategory::of(m.id) == MarkerCategory::Boundary)
        .collect();
    assert_eq!(boundary.len(), 32);
    for m in &boundary {
        let inward = Point2::new(
            m.position.x + 0.1 * m.normal.cos(),
            m.position.y + 0.1 * m.normal.sin(),
        );
        assert!(
            inward.x.abs() < 2.0 && inward.y.abs() < 2.0,
            "marker {} faces out",
            m.id
        );
    }
    assert!((2..=3).contains(&w.obstacles.len()));
    assert!(
        w.markers
            .iter()
            .any(|m| MarkerCategory::of(m.id) == MarkerCategory::Obstacle)
    );
    assert_eq!(w.gates.len(), 2);
    let reds = w
        .blocks
        .iter()
        .filter(|b| b.color == BlockColor::Red)
        .count();
    assert_eq!((reds, w.blocks.len()), (2, 4));
    // Walls hold the boundary and every obstacle outline.
    assert_eq!(w.walls.len(), 4 + 4 * w.obstacles.len());
    let gate = w.gate_pose(&w.gates[0]).unwrap();
    let [a, b] = w.gates[0].markers.map(|id| w.marker(id).unwrap().position);
    assert!((a.distance(b) - 0.2).abs() < 1e-9 && gate.x.abs() == 2.0);
}

#[test]
fn shipped_world_files_load_from_disk() {
    let arena = World::load(&manifest("maps/arena.toml")).unwrap();
    assert_eq!(arena, World::default_arena());
    let wh = World::load(&manifest("maps/warehouse.toml")).unwrap();
    assert_eq!((wh.width, wh.height), (8.0, 6.0));
    let ids: HashSet<u32> = wh.markers.iter().map(|m| m.id).collect();
    assert_eq!(ids.len(), wh.markers.len());
    // Shelf rows carry markers on both faces.
    let shelf: Vec<_> = wh
        .markers
        .iter()
        .filter(|m| (341..=352).contains(&m.id))
        .collect();
    assert_eq!(shelf.len(), 12);
    assert!(
        shelf.iter().any(|m| m.normal.cos() > 0.99) && shelf.iter().any(|m| m.normal.cos() < -0.99)
    );
}

#[test]
fn rasterized_arena_blocks_the_walls_and_frees_the_floor() {
    let w = World::default_arena();
    let g = w.rasterize(0.01);
    assert_eq!((g.width, g.height), (400, 400));
    assert_eq!(g.origin, Point2::new(-2.0, -2.0));
    assert_eq!(g.at(Point2::new(-1.995, 0.3)), OCCUPIED);
    assert_eq!(g.at(Point2::new(1.995, -1.3)), OCCUPIED);
    assert_eq!(g.at(Point2::new(0.5, 0.5)), OCCUPIED, "obstacle");
    assert_eq!(g.at(w.start.position()), FREE);
}

#[test]
fn missing_file_names_the_path() {
    let err = World::load(Path::new("maps/nowhere.toml")).unwrap_err();
    assert!(matches!(err, WorldError::Read { .. }));
    assert!(err.to_string().contains("maps/nowhere.toml"));
}

#[test]
fn duplicate_marker_id_names_both_places() {
    let msg = refuse("\n[[markers]]\nid = 5\nx = 0.0\ny = 0.0\nfacing_deg = 0.0\n");
    assert!(
        msg.contains("markers[0].id") && msg.contains("= 5"),
        "{msg}"
    );
    assert!(
        msg.contains("duplicate") && msg.contains("walls[0].markers"),
        "{msg}"
    );
    assert!(msg.contains("line 9"), "{msg}");
}

#[test]
fn marker_id_outside_its_category_is_refused() {
    let msg =
        refuse("[[obstacles]]\ncenter = [0.5, 0.5]\nsize = [0.2, 0.2]\nmarkers = [301, 17]\n");
    assert!(
        msg.contains("obstacles[0].markers[1]") && msg.contains("= 17"),
        "{msg}"
    );
    assert!(msg.contains("boundary") && msg.contains("301-400"), "{msg}");
    let msg = refuse("[[markers]]\nid = 470\nx = 0.0\ny = 0.0\nfacing_deg = 0.0\n");
    assert!(
        msg.contains("470") && msg.contains("outside every marker range"),
        "{msg}"
    );
}

#[test]
fn gate_markers_must_match_the_gate_colour() {
    let msg = refuse(
        "[[gates]]\ncolor = \"red\"\nmarkers = [501, 502]\ncenter = [2.0, 0.0]\nfacing_deg = 180.0\n",
    );
    assert!(
        msg.contains("gates[0].markers[0]") && msg.contains("501") && msg.contains("red gate"),
        "{msg}"
    );
}

#[test]
fn block_needs_an_odd_even_pair_of_its_colour() {
    let msg = refuse("[[blocks]]\ncolor = \"red\"\nx = 0.5\ny = 0.5\nmarkers = [422, 423]\n");
    assert!(
        msg.contains("blocks[0].markers") && msg.contains("[422, 423]") && msg.contains("odd"),
        "{msg}"
    );
    let msg = refuse("[[blocks]]\ncolor = \"blue\"\nx = 0.5\ny = 0.5\nmarkers = [421, 422]\n");
    assert!(
        msg.contains("blocks[0].markers[0]") && msg.contains("blue block"),
        "{msg}"
    );
}

#[test]
fn unknown_field_is_named_with_its_line() {
    let msg = refuse("[[blocks]]\ncolour = \"red\"\nx = 0.5\ny = 0.5\nmarkers = [421, 422]\n");
    assert!(msg.contains("colour") && msg.contains("line 9"), "{msg}");
}

#[test]
fn things_outside_the_world_are_refused() {
    let msg = refuse("[[walls]]\npoints = [[0.0, 0.0], [3.0, 0.0]]\n");
    assert!(
        msg.contains("walls[1].points[1]") && msg.contains("[3, 0]") && msg.contains("outside"),
        "{msg}"
    );
    let msg = refuse("[[blocks]]\ncolor = \"red\"\nx = 1.99\ny = 0.0\nmarkers = [421, 422]\n");
    assert!(
        msg.contains("blocks[0] corner") && msg.contains("outside"),
        "{msg}"
    );
    let text = HEADER.replace("start = [0.0, 0.0, 0.0]", "start = [0.0, 2.5, 0.0]");
    let msg = World::from_toml(&text, Path::new("maps/bad.toml"))
        .unwrap_err()
        .to_string();
    assert!(msg.contains("`start`") && msg.contains("line 3"), "{msg}");
}

#[test]
fn non_finite_numbers_are_refused() {
    let msg = refuse("[[markers]]\nid = 200\nx = nan\ny = 0.0\nfacing_deg = 0.0\n");
    assert!(
        msg.contains("markers[0]") && msg.contains("NaN") && msg.contains("finite"),
        "{msg}"
    );
    let msg = refuse("[[obstacles]]\ncenter = [0.5, 0.5]\nsize = [inf, 0.2]\n");
    assert!(
        msg.contains("obstacles[0].size[0]") && msg.contains("inf"),
        "{msg}"
    );
}

#[test]
fn degenerate_walls_are_refused() {
    let msg = refuse("[[walls]]\npoints = [[0.0, 0.0]]\n");
    assert!(
        msg.contains("walls[1].points") && msg.contains("at least 2"),
        "{msg}"
    );
    let msg = refuse("[[walls]]\npoints = [[0.0, 0.0], [0.0, 0.0], [1.0, 0.0]]\n");
    assert!(
        msg.contains("walls[1].points[1]") && msg.contains("zero length"),
        "{msg}"
    );
    let msg = refuse("[[walls]]\npoints = []\nclosed = true\n");
    assert!(msg.contains("at least 3"), "{msg}");
}

#[test]
fn generated_ids_may_not_run_past_their_range() {
    let text = HEADER.replace("first_id = 1,", "first_id = 290,");
    let msg = World::from_toml(&text, Path::new("maps/bad.toml"))
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("walls[0].markers.first_id") && msg.contains("290..=321"),
        "{msg}"
    );
    let msg = refuse(
        "[[walls]]\npoints = [[0.0, 0.0], [1.0, 0.0]]\nmarkers = { first_id = 100, spacing = 1e-300 }\n",
    );
    assert!(msg.contains("run past"), "{msg}");
}

#[test]
fn start_inside_an_obstacle_is_refused() {
    let msg = refuse("[[obstacles]]\ncenter = [0.0, 0.0]\nsize = [0.3, 0.3]\n");
    assert!(
        msg.contains("`start`") && msg.contains("obstacles[0]"),
        "{msg}"
    );
}

#[test]
fn syntax_errors_and_empty_names_never_panic() {
    let msg = refuse("[[blocks]\n");
    assert!(msg.contains("line 8"), "{msg}");
    let err = World::from_toml(
        "name = \" \"\nsize = [1.0, 1.0]\nstart = [0.0, 0.0, 0.0]\n",
        Path::new("n.toml"),
    );
    assert!(err.unwrap_err().to_string().contains("`name`"));
    let err = World::from_toml(
        "name = \"x\"\nsize = [-1.0, 1.0]\nstart = [0.0, 0.0, 0.0]\n",
        Path::new("n.toml"),
    );
    assert!(err.unwrap_err().to_string().contains("size[0]"));
}
