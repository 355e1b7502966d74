//! The control loop's schedule (seed 001: a control step every 0.1 s) and the deadman
//! expiries between periods; how regularly the steps ran.

/// A stall longer than this is skipped rather than caught up, seconds.
const MAX_CATCH_UP: f64 = 1.0;
/// Seconds within which a control step counts as due.
pub(super) const TICK_SLACK: f64 = 1e-9;
/// At most one overrun warning per this many seconds.
const WARN_EVERY: f64 = 5.0;

/// When the next control step is due, and how regularly steps have run.
#[derive(Clone, Debug)]
pub(super) struct Schedule {
    period: f64,
    next_tick: f64,
    last_update: f64,
    rate: f64,
    last_warning: f64,
}

/// What is due next, up to a time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Next {
    /// The periodic control step at this time.
    Tick(f64),
    /// A deadman expiry between periods: a command at this time.
    Command(f64),
}

impl Schedule {
    pub(super) fn new(now: f64, period: f64) -> Self {
        Self {
            period,
            next_tick: now,
            last_update: now,
            rate: 1.0 / period,
            last_warning: f64::NEG_INFINITY,
        }
    }

    /// Control steps completed per second, smoothed.
    pub(super) fn rate(&self) -> f64 {
        self.rate
    }

    /// When the next step is due: the next periodic one, or `cutoff` (the deadman's
    /// expiry) when that comes first.
    pub(super) fn next_due(&self, cutoff: Option<f64>) -> f64 {
        cutoff.map_or(self.next_tick, |c| c.min(self.next_tick))
    }

    /// Before catching up to `now`: a warning when the loop overran its period (at most
    /// one per `WARN_EVERY`), and a stall past `MAX_CATCH_UP` skipped.
    pub(super) fn overrun(&mut self, now: f64) -> Option<String> {
        let gap = now - self.last_update;
        if gap <= 1.5 * self.period || self.next_tick > now {
            return None;
        }
        let warning = (now - self.last_warning >= WARN_EVERY).then(|| {
            self.last_warning = now;
            format!(
                "Warning! dt = {gap:.2} s: control loop overran its {:.2} s period",
                self.period
            )
        });
        if now - self.next_tick > MAX_CATCH_UP {
            self.next_tick = now;
        }
        warning
    }

    /// The step due at or before `now` (ticks and `cutoff`, the deadman's expiry), taken
    /// off the schedule; None when nothing is.
    pub(super) fn take_due(&mut self, now: f64, cutoff: Option<f64>) -> Option<Next> {
        let tick = self.next_tick;
        let due = self.next_due(cutoff);
        // A tick due a rounding error after `now` is due now: sums of 0.1 s drift apart.
        if due > now + TICK_SLACK {
            return None;
        }
        if due < tick {
            return Some(Next::Command(due));
        }
        self.next_tick = tick + self.period;
        let dt = due - self.last_update;
        if dt > 0.0 {
            // Exponential smoothing over about ten ticks.
            self.rate += 0.1 * (1.0 / dt - self.rate);
        }
        self.last_update = due;
        Some(Next::Tick(due))
    }
}
