//! Loading a map as a user meets it: one that belongs elsewhere asks first and can be
//! undone, and exploring one world never overwrites another world's autosave.

use crate::common;

use common::scratch;
use navdeck::app::App;
use navdeck::app::mode::Mode;
use navdeck::keymap::parse_key_sequence;
use navdeck::map::grid::OCCUPIED;
use navdeck::map::io;
use navdeck::session::{Session, SessionSpec};
use std::path::PathBuf;

/// The twin in `world` (the built-in arena when None), its maps in `dir`.
fn console(world: Option<PathBuf>, dir: &std::path::Path) -> App {
    let mut app = Session::load(&SessionSpec::twin(world))
        .unwrap()
        .into_app(0.0);
    app.set_maps_dir(dir.to_path_buf());
    app
}

fn press(app: &mut App, keys: &str) {
    navdeck::runners::headless::run(app, &parse_key_sequence(keys).unwrap(), 10.0);
}

fn said(app: &App) -> Vec<String> {
    app.log_book().iter().map(|e| e.text.clone()).collect()
}

/// Walls on the robot's planning map.
fn walls(app: &App) -> usize {
    let grid = app.pilot().belief().occupancy_grid();
    grid.cells.iter().filter(|&&c| c == OCCUPIED).count()
}

#[test]
fn a_map_of_another_world_asks_first_and_its_load_can_be_undone() {
    let dir = scratch("elsewhere");
    for file in ["turtlebot3_world.yaml", "turtlebot3_world.pgm"] {
        std::fs::copy(PathBuf::from("maps").join(file), dir.join(file)).unwrap();
    }
    let mut app = console(None, &dir);
    // Drive about the arena first: the robot has its own walls and floor.
    press(&mut app, &("w".repeat(20) + &"a".repeat(9)).repeat(2));
    let (own_walls, own_landmarks) = (walls(&app), app.pilot().slam().landmark_count());
    assert!(own_walls > 50, "{own_walls}");

    press(&mut app, "l<enter>");
    let asked = said(&app);
    let why = asked
        .iter()
        .find(|l| l.contains("turtlebot3_world does not fit"))
        .unwrap_or_else(|| panic!("{asked:?}"));
    assert!(why.contains("19.2 x 19.2 m"), "{why}");
    assert!(why.contains("Enter again loads it anyway"), "{why}");
    assert_eq!(app.pilot().mode(), Mode::Load, "still choosing");
    assert!(!asked.iter().any(|l| l.starts_with("loaded")), "{asked:?}");
    // The robot still senses as it settles; a merge would add hundreds of walls.
    let asking = walls(&app);
    assert!(
        asking * 10 <= own_walls * 11,
        "nothing merged yet: {asking} against {own_walls}"
    );

    // Enter again: the user meant it.
    press(&mut app, "<enter>");
    assert!(said(&app).iter().any(|l| l.starts_with("loaded")));
    assert_eq!(app.pilot().mode(), Mode::Manual);
    let merged = walls(&app);
    assert!(merged * 10 > asking * 13, "{merged} against {asking}");

    // And takes it back: the arena's map as it was, the filter's landmarks kept.
    press(&mut app, "lu");
    let undone = said(&app);
    assert!(undone.iter().any(|l| l.contains("undone")), "{undone:?}");
    let back = walls(&app);
    assert!(
        back * 10 <= asking * 11,
        "{back} walls after the undo, {asking} before the load, {merged} with it"
    );
    assert!(app.pilot().slam().landmark_count() >= own_landmarks);
    // A second undo has nothing to take back.
    press(&mut app, "u");
    assert!(said(&app).iter().any(|l| l == "no map load to undo"));
}

#[test]
fn moving_the_choice_forgets_the_question() {
    let dir = scratch("moved");
    for file in ["turtlebot3_world.yaml", "turtlebot3_world.pgm"] {
        std::fs::copy(PathBuf::from("maps").join(file), dir.join(file)).unwrap();
        std::fs::copy(
            PathBuf::from("maps").join(file),
            dir.join(format!("z{file}")),
        )
        .unwrap();
    }
    std::fs::rename(dir.join("zturtlebot3_world.pgm"), dir.join("other.pgm")).unwrap();
    let text = std::fs::read_to_string(dir.join("zturtlebot3_world.yaml")).unwrap();
    std::fs::write(
        dir.join("zturtlebot3_world.yaml"),
        text.replace("turtlebot3_world.pgm", "other.pgm"),
    )
    .unwrap();
    let mut app = console(None, &dir);
    press(&mut app, &"w".repeat(15));
    // Asked about the first, then enter on the second asks again instead of loading.
    press(&mut app, "l<enter><down><enter>");
    let asked = said(&app);
    assert!(
        asked
            .iter()
            .any(|l| l.contains("zturtlebot3_world does not fit")),
        "{asked:?}"
    );
    assert!(!asked.iter().any(|l| l.starts_with("loaded")), "{asked:?}");
}

#[test]
fn each_world_keeps_its_own_autosave() {
    use navdeck::app::KeyKind;
    let dir = scratch("autosaves");
    for world in [None, Some(PathBuf::from("tests/worlds/walled_garden.toml"))] {
        let mut app = console(world, &dir);
        let t = app.now();
        app.handle_key("e".parse().unwrap(), KeyKind::Press, t);
        for k in 1..=320 {
            app.update(t + 0.1 * f64::from(k));
        }
    }
    let arena = io::load(&dir.join("autosave-arena.yaml")).unwrap();
    let garden = io::load(&dir.join("autosave-walled-garden.yaml")).unwrap();
    assert_ne!(arena.grid.cells, garden.grid.cells, "two worlds, two maps");
    assert!(!dir.join("autosave.yaml").exists());
}
