//! A fleet explores together: two exploring twins never head for the same ground, each
//! leaves what the other explored, so the pair finishes exploring sooner than one robot;
//! a twin boxed in by the others at the start waits for them to move, and explores.

use navdeck::fleet::Fleet;
use navdeck::geometry::Point2;
use navdeck::keymap::Action;
use navdeck::pilot::mode::Mode;
use navdeck::session::{SessionSpec, fleet};
use navdeck::sim::World;
use navdeck::sim::generate::{GenerateOptions, generate};
use navdeck::tui::deck::Deck;

/// Seed 3's generated world without its blocks: the missions only explore.
fn bare_world() -> (SessionSpec, World) {
    let mut world = generate(&GenerateOptions {
        seed: 3,
        ..GenerateOptions::default()
    })
    .unwrap();
    world.blocks.clear();
    let spec = SessionSpec {
        seed: 3,
        ..SessionSpec::twin(None)
    };
    (spec, world)
}

/// What a fleet's exploration showed: when the last robot had done exploring (its
/// mission ended, or it was on its way back to where it started), and at each control
/// period each robot's exploration goal.
struct Explored {
    finished: f64,
    goals: Vec<Vec<Option<Point2>>>,
}

/// `e` on every robot of `fleet`, run on simulated time until every robot has done
/// exploring, for `limit` seconds at most.
fn explore(mut fleet: Fleet, limit: f64) -> (Fleet, Explored) {
    for m in fleet.members_mut() {
        m.app.apply(Action::ModeExplore);
    }
    let period = fleet.app().config().robot.control_period;
    let mut t = 0.0;
    let mut goals = Vec::new();
    let exploring = |f: &Fleet| {
        (f.members().iter()).any(|m| {
            let pilot = m.app.pilot();
            let done = pilot.mission().is_none_or(|x| x.done_exploring());
            pilot.mode() == Mode::Exploration && !done
        })
    };
    while exploring(&fleet) && t < limit {
        t += period;
        fleet.update(t);
        goals.push(
            (fleet.members().iter())
                .map(|m| m.app.pilot().fleet_frontier())
                .collect(),
        );
    }
    let explored = Explored { finished: t, goals };
    (fleet, explored)
}

#[test]
fn two_twins_explore_apart_and_finish_sooner_than_one() {
    let (spec, world) = bare_world();
    let alone = fleet::twins_in(&spec, world.clone(), 1).unwrap();
    let (_, one) = explore(Fleet::of_sessions(alone, 0.0), 1200.0);
    let pair = fleet::twins_in(&spec, world, 2).unwrap();
    let (pair, two) = explore(Fleet::of_sessions(pair, 0.0), 1200.0);
    let reach = pair.app().config().mission.view_range;
    // Never the same ground at once: while both head for a goal, the goals are apart.
    for (k, now) in two.goals.iter().enumerate() {
        if let [Some(a), Some(b)] = now[..] {
            let apart = a.distance(b);
            assert!(
                apart >= reach,
                "at step {k} goals {a:?} and {b:?}, {apart:.2} m apart"
            );
        }
    }
    // Each went exploring somewhere of its own.
    for robot in 0..2 {
        let own: Vec<Point2> = two.goals.iter().filter_map(|g| g[robot]).collect();
        assert!(!own.is_empty(), "robot {} chose no goal", robot + 1);
    }
    let hits: u32 = (pair.members().iter())
        .map(|m| m.app.link().ground_truth().unwrap().collisions())
        .sum();
    assert_eq!(hits, 0);
    assert!(
        two.finished < one.finished,
        "two robots explored in {:.1} s, one in {:.1} s",
        two.finished,
        one.finished
    );
}

#[test]
fn a_twin_boxed_in_by_the_others_at_the_start_waits_and_then_explores() {
    // Eight twins in the arena: the start's neighbours box some in at first.
    let members = fleet::twins(&SessionSpec::twin(None), 8).unwrap();
    let (fleet, _) = explore(Fleet::of_sessions(members, 0.0), 180.0);
    for m in fleet.members() {
        let driven = m.app.link().ground_truth().unwrap().distance_driven();
        assert!(driven > 1.0, "{} drove {driven:.2} m", m.name);
    }
}
