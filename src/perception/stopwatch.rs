//! Time for latency figures, passed in: the core reads no clock, the edge hands one over.

/// Seconds since some fixed start; only differences are used.
pub trait Stopwatch: Send + Sync {
    fn seconds(&self) -> f64;
}
