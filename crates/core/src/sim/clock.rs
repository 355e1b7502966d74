//! When a periodic sensor fires, counted on the twin's own physics time.

/// Fires at `period`, 2 `period`, ... of twin time; counts instead of accumulating so a
/// long run does not drift.
#[derive(Clone, Debug)]
pub struct SensorClock {
    period: f64,
    fired: u64,
}

impl SensorClock {
    /// A clock at `rate_hz`; a rate that is not a positive number never fires.
    pub fn new(rate_hz: f64) -> Self {
        let period = if rate_hz.is_finite() && rate_hz > 0.0 {
            1.0 / rate_hz
        } else {
            f64::INFINITY
        };
        Self { period, fired: 0 }
    }

    /// True when a firing time has been reached by `now`; several missed firings count as one.
    pub fn due(&mut self, now: f64) -> bool {
        // Slack for time built from many physics steps (0.1 s = 10 x 0.01 s in floating point).
        let now = now + 1e-9;
        if now < (self.fired + 1) as f64 * self.period {
            return false;
        }
        self.fired = (now / self.period).floor() as u64;
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fires_once_per_period_without_drift() {
        let mut c = SensorClock::new(10.0);
        let fired: Vec<u64> = (1..=1000).filter(|k| c.due(*k as f64 * 0.01)).collect();
        assert_eq!(fired.len(), 100);
        assert_eq!(fired[0], 10);
        assert_eq!(fired[99], 1000);
        assert!(!SensorClock::new(0.0).due(1e9));
    }
}
