//! builtin_interfaces: time stamps and durations.

use serde::{Deserialize, Serialize};

/// builtin_interfaces/Time.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Time {
    pub sec: i32,
    pub nanosec: u32,
}

impl Time {
    /// Seconds as a float.
    pub fn seconds(self) -> f64 {
        f64::from(self.sec) + f64::from(self.nanosec) * 1e-9
    }

    /// From seconds since the epoch (saturating outside i32 seconds).
    pub fn from_seconds(t: f64) -> Self {
        let sec = t.floor();
        Self {
            sec: sec.clamp(f64::from(i32::MIN), f64::from(i32::MAX)) as i32,
            nanosec: (((t - sec) * 1e9) as u32).min(999_999_999),
        }
    }
}

/// builtin_interfaces/Duration.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Duration {
    pub sec: i32,
    pub nanosec: u32,
}

impl Duration {
    /// From seconds, rounded to the nanosecond (non-finite or negative: zero; saturating
    /// at i32 seconds).
    pub fn from_seconds(t: f64) -> Self {
        if !(t.is_finite() && t > 0.0) {
            return Self::default();
        }
        let whole = t.floor().min(f64::from(i32::MAX));
        let nanos = ((t - whole) * 1e9).round().min(999_999_999.0);
        Self {
            sec: whole as i32,
            nanosec: nanos as u32,
        }
    }

    pub fn seconds(self) -> f64 {
        f64::from(self.sec) + f64::from(self.nanosec) * 1e-9
    }
}
