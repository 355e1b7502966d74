//! Behaviours under one arbiter (seed 000 §5.3): the priority table, the arbiter that
//! picks the winner each tick, and the pilot's proposals from its modes and safety gate.

pub mod arbiter;
mod collision;
mod fleet;
mod health;
mod propose;
pub mod table;

pub use arbiter::{Arbiter, Proposal, Transition};
pub(crate) use health::{Response, camera_usable};
pub use table::Behaviour;

/// The arbiter and what feeds its safety behaviours: the gate (e-stop, link in doubt),
/// the collision monitor and the sensors' health.
#[derive(Clone, Debug)]
pub(crate) struct Behaviours {
    pub gate: crate::safety::Gate,
    pub arbiter: Arbiter,
    pub collision: collision::CollisionWatch,
    pub health: navdeck_core::health::SensorHealth,
    /// This robot's fleet, when it has one: whom it gives way to.
    pub fleet: fleet::FleetWatch,
}

impl Behaviours {
    pub fn new(settings: &crate::config::Settings) -> Self {
        let radius = settings.robot.footprint_radius;
        Self {
            gate: crate::safety::Gate::default(),
            arbiter: Arbiter::default(),
            collision: collision::CollisionWatch::new(&settings.safety, radius),
            health: navdeck_core::health::SensorHealth::new(settings.safety.health.clone()),
            fleet: fleet::FleetWatch::default(),
        }
    }
}
