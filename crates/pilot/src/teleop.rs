//! Keyboard driving with a deadman: held keys drive, and the robot stops when keys stop.
//!
//! Terminals send no key release unless they speak the kitty keyboard protocol, so a key
//! counts as held until `deadman_timeout` after its last press or auto-repeat. Where
//! release events arrive, a release ends the key at once, and a key that has not yet
//! auto-repeated is given `initial_repeat_delay` before the deadman judges it, so the
//! robot does not stutter in the pause before auto-repeat starts (teleop_twist_keyboard
//! issues 8 and 29 show both failure modes).

use super::config::TeleopConfig;
use navdeck_core::geometry::Twist;

/// Auto-repeat delays of common terminals run from about 0.25 s to 0.66 s (X11's default).
pub const INITIAL_REPEAT_DELAY: f64 = 0.7;

/// The eight drive keys of teleop_twist_keyboard's layout.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DriveKey {
    Forward,
    Backward,
    TurnLeft,
    TurnRight,
    ForwardLeft,
    ForwardRight,
    BackwardLeft,
    BackwardRight,
}

impl DriveKey {
    /// (linear, angular) direction, each -1, 0 or 1.
    pub fn direction(self) -> (i8, i8) {
        match self {
            DriveKey::Forward => (1, 0),
            DriveKey::Backward => (-1, 0),
            DriveKey::TurnLeft => (0, 1),
            DriveKey::TurnRight => (0, -1),
            DriveKey::ForwardLeft => (1, 1),
            DriveKey::ForwardRight => (1, -1),
            // Backs towards the left rear (nose swings right), as teleop_twist_keyboard's `m`.
            DriveKey::BackwardLeft => (-1, -1),
            DriveKey::BackwardRight => (-1, 1),
        }
    }

    /// The name keymap files give the key's action.
    pub fn name(self) -> &'static str {
        match self {
            DriveKey::Forward => "forward",
            DriveKey::Backward => "backward",
            DriveKey::TurnLeft => "turn_left",
            DriveKey::TurnRight => "turn_right",
            DriveKey::ForwardLeft => "forward_left",
            DriveKey::ForwardRight => "forward_right",
            DriveKey::BackwardLeft => "backward_left",
            DriveKey::BackwardRight => "backward_right",
        }
    }
}

/// The speed keys: both speeds, or one, up or down by `speed_step`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpeedChange {
    SpeedUp,
    SpeedDown,
    LinearUp,
    LinearDown,
    AngularUp,
    AngularDown,
}

/// Floors that keep a slowed robot able to move: 1 cm/s and 0.05 rad/s.
const LINEAR_FLOOR: f64 = 0.01;
const ANGULAR_FLOOR: f64 = 0.05;

#[derive(Clone, Copy, Debug, PartialEq)]
struct Held {
    key: DriveKey,
    /// Time of the newest press or repeat.
    last_event: f64,
    repeated: bool,
}

/// Speeds and held drive keys.
#[derive(Clone, Debug)]
pub struct Teleop {
    pub linear_speed: f64,
    pub angular_speed: f64,
    max_linear: f64,
    max_angular: f64,
    step: f64,
    deadman_timeout: f64,
    release_events: bool,
    held: Vec<Held>,
    /// Manual mode's speeds, kept while race mode drives faster.
    kept_speeds: (f64, f64),
}

impl Teleop {
    pub fn new(config: &TeleopConfig, max_linear: f64, max_angular: f64) -> Self {
        Self {
            linear_speed: config.linear_speed.min(max_linear),
            angular_speed: config.angular_speed.min(max_angular),
            max_linear,
            max_angular,
            step: config.speed_step,
            deadman_timeout: config.deadman_timeout,
            release_events: false,
            held: Vec::new(),
            kept_speeds: (0.0, 0.0),
        }
    }

    /// Keeps the speeds now in force, to give back on leaving race mode.
    pub(crate) fn keep_speeds(&mut self) {
        self.kept_speeds = (self.linear_speed, self.angular_speed);
    }

    /// The speeds kept by `keep_speeds`.
    pub(crate) fn kept_speeds(&self) -> (f64, f64) {
        self.kept_speeds
    }

    /// Whether the terminal reports key releases (kitty keyboard protocol).
    pub fn set_release_events(&mut self, on: bool) {
        self.release_events = on;
    }

    pub fn limits(&self) -> (f64, f64) {
        (self.max_linear, self.max_angular)
    }

    /// A press (`repeat == false`) or auto-repeat of a drive key at `now`.
    pub fn press(&mut self, key: DriveKey, now: f64, repeat: bool) {
        match self.held.iter_mut().find(|h| h.key == key) {
            Some(h) => {
                h.repeated |= repeat || now > h.last_event;
                h.last_event = now;
            }
            None => self.held.push(Held {
                key,
                last_event: now,
                repeated: repeat,
            }),
        }
    }

    pub fn release(&mut self, key: DriveKey) {
        self.held.retain(|h| h.key != key);
    }

    /// Forgets every held key: stop, e-stop, mode change.
    pub fn clear(&mut self) {
        self.held.clear();
    }

    /// When a held key's deadman fires: `brake` seconds before its timeout, so that a robot
    /// needing that long to brake is at rest when the timeout ends. With release events, a
    /// key not yet auto-repeating keeps `INITIAL_REPEAT_DELAY`: its release will stop it.
    fn expiry(&self, h: &Held, brake: f64) -> f64 {
        let deadman = (self.deadman_timeout - brake).max(0.0);
        if self.release_events && !h.repeated {
            h.last_event + deadman.max(INITIAL_REPEAT_DELAY)
        } else {
            h.last_event + deadman
        }
    }

    /// Drive keys still held at `now`, dropping those whose deadman fired.
    pub fn held_at(&mut self, now: f64, brake: f64) -> Vec<DriveKey> {
        let kept: Vec<Held> = (self.held.iter().copied())
            .filter(|h| now < self.expiry(h, brake))
            .collect();
        self.held = kept;
        self.held.iter().map(|h| h.key).collect()
    }

    /// The twist the held keys ask for at `now`: the sum of their directions, each axis
    /// clamped to one unit, scaled by the current speeds.
    pub fn twist(&mut self, now: f64, brake: f64) -> Twist {
        let (mut lin, mut ang) = (0i32, 0i32);
        for key in self.held_at(now, brake) {
            let (l, a) = key.direction();
            lin += i32::from(l);
            ang += i32::from(a);
        }
        Twist::new(
            f64::from(lin.clamp(-1, 1)) * self.linear_speed,
            f64::from(ang.clamp(-1, 1)) * self.angular_speed,
        )
    }

    /// Time when the earliest held key's deadman fires (`brake` seconds early), if any is held.
    pub fn next_expiry(&self, brake: f64) -> Option<f64> {
        self.held
            .iter()
            .map(|h| self.expiry(h, brake))
            .reduce(f64::min)
    }

    /// New speed limits (switching between manual and race), and speeds within them.
    pub fn set_limits(&mut self, max_linear: f64, max_angular: f64, speeds: (f64, f64)) {
        self.max_linear = max_linear;
        self.max_angular = max_angular;
        self.linear_speed = speeds.0.min(max_linear);
        self.angular_speed = speeds.1.min(max_angular);
    }

    /// Applies a speed key; returns false when the speeds were already at their limit.
    pub fn adjust(&mut self, change: SpeedChange) -> bool {
        // Both speeds scale by one factor, stopped short by whichever reaches its limit
        // first, so their ratio (the turn a forward-left key drives) stays.
        let (v, w) = (self.linear_speed, self.angular_speed);
        let both_up = self
            .step
            .min(self.max_linear / v)
            .min(self.max_angular / w)
            .max(1.0);
        let both_down = (1.0 / self.step)
            .max(LINEAR_FLOOR / v)
            .max(ANGULAR_FLOOR / w)
            .min(1.0);
        let (lin, ang) = match change {
            SpeedChange::SpeedUp => (both_up, both_up),
            SpeedChange::SpeedDown => (both_down, both_down),
            SpeedChange::LinearUp => (self.step, 1.0),
            SpeedChange::LinearDown => (1.0 / self.step, 1.0),
            SpeedChange::AngularUp => (1.0, self.step),
            SpeedChange::AngularDown => (1.0, 1.0 / self.step),
        };
        let before = (self.linear_speed, self.angular_speed);
        // A speed a rounding error short of its limit is at it (v * (max / v) may not
        // give max back exactly).
        let at_limit = |x: f64, max: f64| if max - x < 1e-9 * max { max } else { x };
        self.linear_speed = at_limit(
            (v * lin).clamp(LINEAR_FLOOR, self.max_linear),
            self.max_linear,
        );
        self.angular_speed = at_limit(
            (w * ang).clamp(ANGULAR_FLOOR, self.max_angular),
            self.max_angular,
        );
        before != (self.linear_speed, self.angular_speed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn teleop() -> Teleop {
        Teleop::new(&TeleopConfig::default(), 0.4, 4.0)
    }

    #[test]
    fn speed_keys_keep_the_ratio_at_a_limit_and_say_when_nothing_changes() {
        // Limits 0.4 m/s and 4 rad/s: the turn rate reaches its limit first.
        let mut t = Teleop::new(&TeleopConfig::default(), 0.4, 2.0);
        let ratio = t.linear_speed / t.angular_speed;
        while t.adjust(SpeedChange::SpeedUp) {}
        assert!((t.linear_speed / t.angular_speed - ratio).abs() < 1e-12);
        assert!(
            (t.angular_speed - 2.0).abs() < 1e-12,
            "stopped at the turn limit"
        );
        assert!(t.linear_speed < 0.4);
        assert!(!t.adjust(SpeedChange::SpeedUp), "nothing left to raise");
        while t.adjust(SpeedChange::SpeedDown) {}
        assert!((t.linear_speed / t.angular_speed - ratio).abs() < 1e-9);
        // One speed on its own still goes to its own limit.
        assert!(t.adjust(SpeedChange::LinearUp));
    }

    #[test]
    fn tap_drives_until_deadman_then_stops() {
        let mut t = teleop();
        t.press(DriveKey::Forward, 1.0, false);
        assert_eq!(t.twist(1.2, 0.0).linear, 0.15);
        assert_eq!(t.twist(1.49, 0.0).linear, 0.15);
        assert!(t.twist(1.5, 0.0).is_zero());
    }

    #[test]
    fn auto_repeat_keeps_driving_without_gaps() {
        let mut t = teleop();
        // Auto-repeat at 30 Hz for two seconds: never a zero in between.
        let mut now = 0.0;
        t.press(DriveKey::Forward, now, false);
        while now < 2.0 {
            assert_eq!(t.twist(now, 0.0).linear, 0.15, "stutter at {now}");
            now += 1.0 / 30.0;
            t.press(DriveKey::Forward, now, true);
        }
        assert!(t.twist(now + 0.5, 0.0).is_zero());
    }

    #[test]
    fn release_stops_at_once_and_grace_covers_repeat_delay() {
        let mut t = teleop();
        t.set_release_events(true);
        t.press(DriveKey::Forward, 0.0, false);
        // 0.6 s before the first repeat: still driving with release events on.
        assert_eq!(t.twist(0.6, 0.0).linear, 0.15);
        t.press(DriveKey::Forward, 0.65, true);
        t.release(DriveKey::Forward);
        assert!(t.twist(0.66, 0.0).is_zero());
    }

    #[test]
    fn keys_combine_and_cancel() {
        let mut t = teleop();
        t.press(DriveKey::Forward, 0.0, false);
        t.press(DriveKey::TurnLeft, 0.0, false);
        let tw = t.twist(0.1, 0.0);
        assert!(tw.linear > 0.0 && tw.angular > 0.0);
        t.press(DriveKey::Backward, 0.0, false);
        assert_eq!(t.twist(0.1, 0.0).linear, 0.0);
    }

    #[test]
    fn speed_keys_respect_limits() {
        let mut t = teleop();
        for _ in 0..100 {
            t.adjust(SpeedChange::SpeedUp);
        }
        assert_eq!((t.linear_speed, t.angular_speed), (0.4, 4.0));
        assert!(!t.adjust(SpeedChange::SpeedUp));
        assert!(t.adjust(SpeedChange::LinearDown));
        assert!(t.linear_speed < 0.4 && t.angular_speed == 4.0);
    }
}
