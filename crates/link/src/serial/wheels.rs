//! Between the console's units and the firmware's: (v, w) to wheel targets in encoder ticks
//! per PID frame, and encoder counts back to wheel travel.

use crate::WheelTravel;
use navdeck_core::geometry::Twist;
use std::f64::consts::PI;

/// The base's geometry and the firmware's encoder and PID figures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WheelGeometry {
    pub wheel_radius: f64,
    pub track: f64,
    pub counts_per_rev: f64,
    pub pid_rate_hz: f64,
}

impl WheelGeometry {
    /// Wheel rim speeds for a twist, m/s: v -+ w b / 2 (seed 001's differential drive).
    pub fn wheel_speeds(&self, twist: Twist) -> (f64, f64) {
        let half = twist.angular * self.track / 2.0;
        (twist.linear - half, twist.linear + half)
    }

    /// Encoder ticks per PID frame at rim speed `speed`: speed / (2 pi r) revolutions per
    /// second, times counts per revolution, over frames per second.
    pub fn ticks_per_frame(&self, speed: f64) -> f64 {
        speed / (2.0 * PI * self.wheel_radius) * self.counts_per_rev / self.pid_rate_hz
    }

    /// Metres of rim travel for `counts` encoder counts: 2 pi r counts / counts_per_rev.
    pub fn travel(&self, counts: i64) -> f64 {
        2.0 * PI * self.wheel_radius * counts as f64 / self.counts_per_rev
    }
}

/// Turns an exact, fractional ticks-per-frame rate into the integers the firmware takes,
/// so that the ticks commanded over time add up to the exact rate (first-order delta-sigma):
/// the ticks owed so far are spread over the next `horizon` frames.
#[derive(Clone, Debug, Default)]
pub struct Dither {
    /// Ticks commanded too few (positive) or too many since the rate was set.
    owed: f64,
    exact: f64,
    sent: i32,
    since: f64,
}

impl Dither {
    /// The integer target for the frames from `frame` (PID frames since any fixed origin,
    /// fractional) on, for an exact rate of `exact` ticks per frame; `horizon` is how many
    /// frames until the next call.
    pub fn next(&mut self, exact: f64, frame: f64, horizon: f64) -> i32 {
        let elapsed = (frame - self.since).max(0.0);
        self.owed += (self.exact - f64::from(self.sent)) * elapsed;
        // A new direction or a stop forgives the debt: it belongs to the old motion.
        if exact == 0.0 || exact.signum() != self.exact.signum() {
            self.owed = 0.0;
        }
        // At most one tick per frame of correction, so a long stall cannot build a lurch.
        self.owed = self.owed.clamp(-horizon, horizon);
        let limit = f64::from(i16::MAX);
        let sent = (exact + self.owed / horizon.max(1.0))
            .round()
            .clamp(-limit, limit) as i32;
        self.exact = exact.clamp(-limit, limit);
        self.sent = sent;
        self.since = frame;
        sent
    }
}

/// What one encoder reading amounts to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Reading {
    /// The first reading on a connection: nothing to compare it with.
    Baseline,
    Travel(WheelTravel),
    /// Counts moved further than the wheels could have: (left, right) counts, not used.
    Jump(i64, i64),
}

/// Turns successive encoder counts into wheel travel.
#[derive(Clone, Debug)]
pub struct Odometer {
    geometry: WheelGeometry,
    /// Fastest rim speed believable, m/s.
    max_speed: f64,
    last: Option<(i32, i32)>,
}

/// Counts of slack on the jump bound, for a reading taken just as a count ticked over.
const JUMP_SLACK_COUNTS: f64 = 2.0;

impl Odometer {
    pub fn new(geometry: WheelGeometry, max_speed: f64) -> Self {
        Self {
            geometry,
            max_speed,
            last: None,
        }
    }

    /// Forget the previous reading (a new connection; the firmware may have reset).
    pub fn rebase(&mut self) {
        self.last = None;
    }

    /// Counts read `dt` seconds after the previous reading. The firmware's counters are
    /// `long`s, so differences are taken modulo 2^32 and cross the wrap-around unharmed.
    pub fn read(&mut self, left: i32, right: i32, dt: f64) -> Reading {
        let Some((l0, r0)) = self.last.replace((left, right)) else {
            return Reading::Baseline;
        };
        let dl = i64::from(left.wrapping_sub(l0));
        let dr = i64::from(right.wrapping_sub(r0));
        let bound = self.geometry.counts_per_rev * self.max_speed * dt.max(0.0)
            / (2.0 * PI * self.geometry.wheel_radius)
            + JUMP_SLACK_COUNTS;
        if dl.abs() as f64 > bound || dr.abs() as f64 > bound {
            return Reading::Jump(dl, dr);
        }
        Reading::Travel(WheelTravel {
            left: self.geometry.travel(dl),
            right: self.geometry.travel(dr),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const GEOMETRY: WheelGeometry = WheelGeometry {
        wheel_radius: 0.05,
        track: 0.3,
        counts_per_rev: 1200.0,
        pid_rate_hz: 30.0,
    };

    #[test]
    fn a_twist_becomes_ticks_per_frame() {
        // Worked by hand: w = 1 rad/s on a 0.3 m track moves the rims -+0.15 m/s about v = 0.2.
        let (l, r) = GEOMETRY.wheel_speeds(Twist::new(0.2, 1.0));
        assert!((l - 0.05).abs() < 1e-12 && (r - 0.35).abs() < 1e-12);
        // 0.2 pi m/s on a 0.05 m wheel is 2 rev/s = 2400 counts/s = 80 ticks per 1/30 s frame.
        assert!((GEOMETRY.ticks_per_frame(0.2 * PI) - 80.0).abs() < 1e-9);
        assert!((GEOMETRY.travel(600) - 0.05 * PI).abs() < 1e-12);
    }

    #[test]
    fn dithered_targets_add_up_to_the_exact_rate() {
        // 2.4 ticks per frame, re-derived every 3 frames for 10 s: 300 frames, 720 ticks.
        let mut d = Dither::default();
        let mut total = 0i64;
        let mut seen = std::collections::BTreeSet::new();
        for k in 0..100 {
            let sent = d.next(2.4, f64::from(k) * 3.0, 3.0);
            seen.insert(sent);
            total += i64::from(sent) * 3;
        }
        assert!((total - 720).abs() <= 3, "{total}");
        assert_eq!(seen.into_iter().collect::<Vec<_>>(), vec![2, 3]);
        // Rounding alone would have sent 2 throughout: 600 ticks, 17 % slow.
    }

    #[test]
    fn whole_rates_are_sent_unchanged_and_a_stop_is_exact() {
        let mut d = Dither::default();
        for k in 0..10 {
            assert_eq!(d.next(-7.0, f64::from(k) * 3.0, 3.0), -7);
        }
        d.next(0.4, 30.0, 3.0);
        assert_eq!(d.next(0.0, 33.0, 3.0), 0);
        assert_eq!(d.next(0.0, 36.0, 3.0), 0);
    }

    #[test]
    fn counts_become_travel_across_the_wrap_around() {
        let mut odo = Odometer::new(GEOMETRY, 1.0);
        assert_eq!(odo.read(i32::MAX - 100, -5, 0.2), Reading::Baseline);
        // 300 counts forward on the left, crossing i32::MAX; 300 back on the right.
        let Reading::Travel(t) = odo.read(i32::MIN + 199, -305, 0.2) else {
            panic!("not travel")
        };
        assert!((t.left - GEOMETRY.travel(300)).abs() < 1e-12, "{t:?}");
        assert!((t.right + GEOMETRY.travel(300)).abs() < 1e-12, "{t:?}");
    }

    #[test]
    fn impossible_jumps_are_refused_and_the_next_reading_is_measured_from_them() {
        let mut odo = Odometer::new(GEOMETRY, 1.0);
        odo.read(0, 0, 0.05);
        // 1 m/s for 0.05 s is 0.05 m: 191 counts; a reset to a far count is not travel.
        assert_eq!(odo.read(100_000, 0, 0.05), Reading::Jump(100_000, 0));
        assert!(matches!(odo.read(100_010, 10, 0.05), Reading::Travel(_)));
        odo.rebase();
        assert_eq!(odo.read(5, 5, 0.05), Reading::Baseline);
    }
}
