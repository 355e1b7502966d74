//! The one clock trait: seconds since some fixed start, handed in from the edge. The core
//! and the pilot read no clock of their own; the console passes the wall clock, tests and
//! headless runs a hand-turned one, and timing figures (planning, camera latency) use
//! whichever they were given.

/// Seconds since some fixed start; only differences matter.
pub trait Clock: Send + Sync {
    fn now(&self) -> f64;
}
