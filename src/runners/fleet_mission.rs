//! `navdeck mission --robots N`: N twins in one world explore and deliver together on
//! simulated time (each its own mission, blocks claimed one robot at a time, robots
//! giving way to each other), scored against the twin's truth.

use crate::fleet::Fleet;
use crate::keymap::Action;
use crate::mission::drop_places::AT_GATE;
use crate::pilot::mode::Mode;
use crate::session::Session;
use crate::sim::GroundTruth;
use crate::tui::deck::Deck;
use serde::Serialize;

/// One fleet mission's outcome.
#[derive(Clone, Debug, Serialize)]
pub struct FleetMissionReport {
    pub world: String,
    pub seed: u64,
    pub robots: usize,
    /// Blocks at their gates and let go, by the twin's truth.
    pub true_delivered: usize,
    pub total: usize,
    /// "delivered all", "time limit" or "all stopped" (every mission ended first).
    pub outcome: String,
    /// Simulated seconds to the last delivery, or to the end.
    pub sim_time: f64,
    /// Contacts with walls, obstacles and each other, summed over the robots.
    pub collisions: u32,
    /// Of those, contacts between robots.
    pub robot_hits: u32,
    /// Blocks each robot's own mission delivered.
    pub delivered_by: Vec<usize>,
    pub wall_time_s: Option<f64>,
}

impl FleetMissionReport {
    pub fn success(&self) -> bool {
        self.true_delivered == self.total && self.collisions == 0
    }
}

/// Blocks let go at a gate of their colour in `truth`'s world.
fn delivered(truth: &dyn GroundTruth) -> usize {
    let world = truth.world();
    (truth.blocks().iter())
        .filter(|b| !b.held)
        .filter(|b| {
            (world.gates.iter())
                .filter(|g| g.color == b.color)
                .any(|g| {
                    (world.gate_pose(g))
                        .is_some_and(|p| p.position().distance(b.pose.position()) < AT_GATE)
                })
        })
        .count()
}

/// Runs the fleet of `members` (twins of one world) from `e` on every robot until every
/// block is delivered, every mission has ended, or `time_limit` simulated seconds.
pub fn run(members: Vec<(String, Session)>, seed: u64, time_limit: f64) -> FleetMissionReport {
    let robots = members.len();
    let mut fleet = Fleet::of_sessions(members, 0.0);
    for m in fleet.members_mut() {
        m.app.apply(Action::ModeExplore);
    }
    let period = fleet.app().config().robot.control_period;
    let truth = |f: &Fleet| -> (usize, usize) {
        let twin = f.app().link().ground_truth().expect("a fleet of twins");
        (delivered(twin), twin.world().blocks.len())
    };
    let exploring = |f: &Fleet| {
        (f.members().iter())
            .any(|m| m.app.pilot().mode() == Mode::Exploration && m.app.pilot().is_busy())
    };
    let mut t = 0.0;
    let outcome = loop {
        let (done, total) = truth(&fleet);
        if done == total {
            break "delivered all";
        }
        if !exploring(&fleet) {
            break "all stopped";
        }
        if t >= time_limit {
            break "time limit";
        }
        t += period;
        fleet.update(t);
    };
    fleet.shutdown("mission ended");
    let (true_delivered, total) = truth(&fleet);
    let twins = fleet
        .members()
        .iter()
        .filter_map(|m| m.app.link().ground_truth());
    let (collisions, robot_hits) = twins.fold((0, 0), |(c, h), tw| {
        (c + tw.collisions(), h + tw.robot_hits())
    });
    FleetMissionReport {
        world: fleet
            .app()
            .link()
            .ground_truth()
            .map_or(String::new(), |t| t.world().name.clone()),
        seed,
        robots,
        true_delivered,
        total,
        outcome: outcome.into(),
        sim_time: t,
        collisions,
        robot_hits,
        delivered_by: (fleet.members().iter())
            .map(|m| m.app.pilot().delivered_ids().len())
            .collect(),
        wall_time_s: None,
    }
}
