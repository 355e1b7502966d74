//! How often messages arrive, over the last few seconds of session time.

use std::collections::VecDeque;

/// Seconds of arrivals a rate is taken over.
const WINDOW: f64 = 2.0;

#[derive(Clone, Debug, Default)]
pub struct RateMeter {
    arrivals: VecDeque<f64>,
    /// When the first message arrived: before a whole window has passed, the rate is
    /// taken since then.
    first: Option<f64>,
}

impl RateMeter {
    /// A message arrived at `now` (session seconds).
    pub fn note(&mut self, now: f64) {
        self.first.get_or_insert(now);
        self.arrivals.push_back(now);
        while self.arrivals.front().is_some_and(|&t| t <= now - WINDOW) {
            self.arrivals.pop_front();
        }
    }

    /// Messages a second at `now`, over the last `WINDOW` seconds or since the first
    /// message when that is more recent; `None` before anything arrived.
    pub fn rate(&self, now: f64) -> Option<f64> {
        let first = self.first?;
        // A second at least: in its first second a topic's rate climbs to its own,
        // rather than one early batch reading as a burst.
        let span = WINDOW.min(now - first).max(1.0);
        let recent = self.arrivals.iter().filter(|&&t| t > now - WINDOW).count();
        Some(recent as f64 / span)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thirty_a_second_reads_thirty_and_silence_reads_zero() {
        let mut meter = RateMeter::default();
        assert_eq!(meter.rate(1.0), None);
        // Batches of three every tenth of a second, as a 10 Hz poll sees a 30 Hz topic.
        for k in 1..=50 {
            for _ in 0..3 {
                meter.note(k as f64 * 0.1);
            }
        }
        let rate = meter.rate(5.0).unwrap();
        assert!((rate - 30.0).abs() < 1.0, "{rate}");
        assert_eq!(meter.rate(8.0), Some(0.0));
        // A topic that started 1.5 s ago reads its own rate; one that started half a
        // second ago reads less, never more.
        let mut late = RateMeter::default();
        for k in 0..=15 {
            for _ in 0..3 {
                late.note(10.0 + k as f64 * 0.1);
            }
        }
        let rate = late.rate(11.5).unwrap();
        assert!((rate - 32.0).abs() < 1.0, "{rate}: 48 in 1.5 s");
        let mut early = RateMeter::default();
        for _ in 0..3 {
            early.note(20.0);
        }
        assert_eq!(early.rate(20.0), Some(3.0));
    }
}
