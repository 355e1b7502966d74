//! Sensor health (seed 000 §1.4 and §7.2.1, graceful degradation): for each sensor, when
//! it last delivered usable data, whether it is lost (silent past its timeout) and each
//! outage with when it began and ended. The pilot decides what a loss changes; this keeps
//! the books. Time is passed in.

pub mod config;
mod sensor;

pub use config::HealthConfig;
pub use sensor::Sensor;

use serde::Serialize;

/// Outages kept, oldest dropped first.
pub const OUTAGES_KEPT: usize = 100;
/// A sensor's timeout is at least this many of its usual intervals, so that a slow sensor
/// (a camera at 0.5 Hz) is not lost between two frames.
const INTERVALS_PER_TIMEOUT: f64 = 3.0;
/// Weight of the newest interval in the usual interval's running mean.
const INTERVAL_WEIGHT: f64 = 0.1;

/// One time a sensor was lost.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Outage {
    pub sensor: Sensor,
    /// When the pilot declared it lost, seconds.
    pub lost_at: f64,
    /// When it last delivered usable data before that.
    pub last_good: f64,
    /// When usable data came again; `None` while it is still lost.
    pub recovered_at: Option<f64>,
}

/// A sensor lost or recovered, for the log.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Change {
    /// Lost at the time checked, after this many seconds without usable data.
    Lost { sensor: Sensor, silent_for: f64 },
    /// Back after an outage of this many seconds.
    Recovered { sensor: Sensor, after: f64 },
}

#[derive(Clone, Copy, Debug, Default)]
struct Watch {
    last_good: Option<f64>,
    /// The running mean of the intervals between usable data, seconds.
    interval: Option<f64>,
    lost: bool,
}

/// Every sensor's health; see the module comment.
#[derive(Clone, Debug)]
pub struct SensorHealth {
    config: HealthConfig,
    watches: [Watch; Sensor::ALL.len()],
    outages: Vec<Outage>,
}

impl SensorHealth {
    pub fn new(config: HealthConfig) -> Self {
        Self {
            config,
            watches: [Watch::default(); Sensor::ALL.len()],
            outages: Vec::new(),
        }
    }

    pub fn config(&self) -> &HealthConfig {
        &self.config
    }

    /// `sensor` delivered usable data at `t`; a recovery when it was lost.
    pub fn good(&mut self, sensor: Sensor, t: f64) -> Option<Change> {
        let timeout = self.configured_timeout(sensor);
        let w = &mut self.watches[sensor.index()];
        if let Some(last) = w.last_good {
            let gap = t - last;
            // An outage's gap is not a usual interval.
            if gap > 0.0 && gap <= timeout {
                let mean = w.interval.unwrap_or(gap);
                w.interval = Some(mean + INTERVAL_WEIGHT * (gap - mean));
            }
        }
        w.last_good = Some(t);
        if !w.lost {
            return None;
        }
        w.lost = false;
        let outage = self.outages.iter_mut().rev().find(|o| o.sensor == sensor)?;
        outage.recovered_at = Some(t);
        Some(Change::Recovered {
            sensor,
            after: t - outage.last_good,
        })
    }

    /// The sensors newly lost at `t`: silent past their timeout since they last delivered.
    /// A sensor that never delivered is absent, not lost.
    pub fn check(&mut self, t: f64) -> Vec<Change> {
        let mut changes = Vec::new();
        for sensor in Sensor::ALL {
            let timeout = self.timeout(sensor);
            let w = &mut self.watches[sensor.index()];
            let Some(last) = w.last_good else { continue };
            if w.lost || t - last <= timeout {
                continue;
            }
            w.lost = true;
            if self.outages.len() == OUTAGES_KEPT {
                self.outages.remove(0);
            }
            self.outages.push(Outage {
                sensor,
                lost_at: t,
                last_good: last,
                recovered_at: None,
            });
            changes.push(Change::Lost {
                sensor,
                silent_for: t - last,
            });
        }
        changes
    }

    /// Forgets when each sensor last delivered, keeping the outages: after a time the
    /// pilot could not hear the robot at all (the link was lost), the sensors are judged
    /// afresh from their next data.
    pub fn restart(&mut self) {
        for w in &mut self.watches {
            w.last_good = None;
        }
    }

    pub fn is_lost(&self, sensor: Sensor) -> bool {
        self.watches[sensor.index()].lost
    }

    /// Whether `sensor` has delivered usable data this session.
    pub fn has_reported(&self, sensor: Sensor) -> bool {
        self.watches[sensor.index()].last_good.is_some()
    }

    /// The sensors lost now, in the order of `Sensor::ALL`.
    pub fn lost(&self) -> Vec<Sensor> {
        Sensor::ALL
            .into_iter()
            .filter(|s| self.is_lost(*s))
            .collect()
    }

    /// When the current outage of `sensor` began, if it is lost.
    pub fn lost_since(&self, sensor: Sensor) -> Option<f64> {
        if !self.is_lost(sensor) {
            return None;
        }
        let outage = self.outages.iter().rev().find(|o| o.sensor == sensor)?;
        Some(outage.lost_at)
    }

    /// The outages so far (the last `OUTAGES_KEPT`), oldest first.
    pub fn outages(&self) -> &[Outage] {
        &self.outages
    }

    /// Seconds of silence after which `sensor` counts as lost: its configured timeout, or
    /// `INTERVALS_PER_TIMEOUT` of its usual intervals when that is longer.
    pub fn timeout(&self, sensor: Sensor) -> f64 {
        let usual = self.watches[sensor.index()].interval.unwrap_or(0.0);
        self.configured_timeout(sensor)
            .max(INTERVALS_PER_TIMEOUT * usual)
    }

    fn configured_timeout(&self, sensor: Sensor) -> f64 {
        let c = &self.config;
        match sensor {
            Sensor::Odometry => c.odometry_timeout,
            Sensor::Lidar => c.lidar_timeout,
            Sensor::Camera => c.camera_timeout,
            Sensor::Arm => c.arm_timeout,
        }
    }
}

#[cfg(test)]
mod tests;
