//! Blocks and gates read from the filter's landmarks match where the twin put them.

use crate::common;

use common::default_app;
use navdeck::keymap::parse_key_sequence;
use navdeck::mission::objects::Objects;
use navdeck::runners::headless;
use std::collections::BTreeMap;

#[test]
fn blocks_and_gates_from_a_drive_round_the_arena_match_the_twin() {
    let mut app = default_app();
    let keys = ("w".repeat(30) + &"a".repeat(9)).repeat(12);
    headless::run(&mut app, &parse_key_sequence(&keys).unwrap(), 10.0);
    let landmarks: BTreeMap<_, _> = app
        .pilot()
        .slam()
        .landmarks()
        .map(|l| (l.id, l.mean))
        .collect();
    let mut objects = Objects::default();
    let (robot, map) = (app.pilot().estimated_pose(), app.pilot().belief().costmap());
    objects.update(&landmarks, robot.position(), 0.05, map);
    let twin = app.link().ground_truth().unwrap();
    let confirmed: Vec<_> = objects.blocks().filter(|b| b.confirmed).collect();
    assert!(
        !confirmed.is_empty(),
        "the drive saw at least one block whole"
    );
    for block in confirmed {
        let truth = twin
            .blocks()
            .iter()
            .find(|t| t.markers == block.markers)
            .unwrap();
        let error = block.position.distance(truth.pose.position());
        assert!(
            error < 0.06,
            "block {:?} off by {error:.3} m",
            block.markers
        );
    }
    assert!(objects.gates().count() >= 1, "the drive saw a gate");
    for gate in objects.gates() {
        let world = twin.world();
        let twin_gate = world
            .gates
            .iter()
            .find(|g| g.markers == gate.markers)
            .unwrap();
        let truth = world.gate_pose(twin_gate).unwrap();
        assert!(
            gate.center.distance(truth.position()) < 0.08,
            "{gate:?} vs {truth:?}"
        );
        let facing = truth.theta.sin_cos();
        assert!(
            gate.normal.0 * facing.1 + gate.normal.1 * facing.0 > 0.9,
            "{gate:?}"
        );
    }
}
