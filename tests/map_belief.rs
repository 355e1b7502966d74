//! The planning map as the planner sees it: walls from boundary markers, obstacles from
//! the lidar, unknown until observed, and updates that touch only what changed.

use navdeck::config::Config;
use navdeck::geometry::{Point2, Pose2};
use navdeck::map::belief::BeliefMap;
use navdeck::map::config::MapConfig;
use navdeck::map::costmap::{INFLATED, LETHAL, NO_INFORMATION, is_lethal};
use navdeck::sim::{Twin, World};

fn map() -> BeliefMap {
    BeliefMap::new(&MapConfig::default(), (4.0, 4.0))
}

#[test]
fn an_empty_map_knows_nothing() {
    let m = map();
    assert_eq!(m.costmap().width, 400, "seed 001: 4 m at 1 cm");
    assert!(m.costmap().cost.iter().all(|&c| c == NO_INFORMATION));
}

#[test]
fn boundary_markers_wall_off_the_gap_between_them() {
    let mut m = map();
    m.update_landmarks([(1, Point2::new(-1.0, -1.9)), (2, Point2::new(-0.5, -1.9))]);
    let c = m.costmap();
    // Midway between the markers, on the wall line: lethal, not just inflated.
    assert_eq!(c.at(Point2::new(-0.75, -1.9)), LETHAL);
    // 0.25 m off the wall: seed 001's 0.7 ring.
    assert_eq!(c.at(Point2::new(-0.75, -1.65)), INFLATED);
    // Far away: still unknown.
    assert_eq!(c.at(Point2::new(1.0, 1.0)), NO_INFORMATION);
}

#[test]
fn a_moved_landmark_recomputes_only_its_neighbourhood() {
    let mut m = map();
    let ids: Vec<(u32, Point2)> = (0..20)
        .map(|k| (301 + k, Point2::new(-1.5 + 0.15 * f64::from(k), 1.0)))
        .collect();
    m.update_landmarks(ids.clone());
    let (work, revision) = (m.recomputed_cells(), m.revision());
    // The filter nudges every landmark by less than a cell: nothing to do.
    m.update_landmarks(
        ids.iter()
            .map(|&(id, p)| (id, Point2::new(p.x + 0.003, p.y))),
    );
    assert_eq!(m.recomputed_cells(), work);
    assert_eq!(m.revision(), revision);
    // One landmark moves 10 cm: only the discs around its old and new places are redone.
    m.update_landmarks([(305, Point2::new(-0.9, 0.9))]);
    let redone = m.recomputed_cells() - work;
    let reach = 0.30 + 0.20;
    let disc_square = (2.0 * reach / 0.01 + 1.0_f64).powi(2) as u64;
    assert!(redone <= 2 * disc_square, "{redone} cells redone");
    assert!(redone < 160_000 / 4, "far fewer than a rebuild");
    assert!(m.revision() > revision);
    assert_eq!(m.costmap().at(Point2::new(-0.9, 0.9)), LETHAL);
}

#[test]
fn the_twin_lidar_marks_walls_occupied_and_open_floor_free() {
    let config = Config::default();
    let mut twin = Twin::new(World::default_arena(), &config.robot, &config.sim, 7);
    let mut m = map();
    for _ in 0..10 {
        twin.step(0.2);
        if let Some(scan) = twin.take_frame().scan {
            m.observe_scan(twin.pose(), &scan);
        }
    }
    let c = m.costmap();
    let start: Pose2 = twin.pose();
    // The south wall (y = -2), 0.5 m to the robot's right: lethal along it.
    for x in [-1.5, -1.0, -0.5] {
        assert!(is_lethal(c.at(Point2::new(x, -1.97))), "wall at x {x}");
    }
    // The floor between the robot and the wall was crossed by beams: free.
    assert_eq!(c.at(Point2::new(start.x + 0.2, start.y + 0.6)), 0);
    // Box 1 (0.3 m square at (0.5, 0.5)) shows the robot two faces: lethal inside them.
    assert!(is_lethal(c.at(Point2::new(0.5, 0.4))));
    assert!(is_lethal(c.at(Point2::new(0.4, 0.5))));
}
