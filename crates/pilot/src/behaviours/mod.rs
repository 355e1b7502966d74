//! Behaviours under one arbiter (seed 000 §5.3): the priority table, the arbiter that
//! picks the winner each tick, and the pilot's proposals from its modes and safety gate.

pub mod arbiter;
mod propose;
pub mod table;

pub use arbiter::{Arbiter, Proposal, Transition};
pub use table::Behaviour;

/// The arbiter and what feeds its safety behaviours: the gate (e-stop, link in doubt).
#[derive(Clone, Debug, Default)]
pub(crate) struct Behaviours {
    pub gate: crate::safety::Gate,
    pub arbiter: Arbiter,
}
