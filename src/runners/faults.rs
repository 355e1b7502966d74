//! The faults injected into a run's twin (`--fault`, `:fault`), as the runs' JSON lists
//! them: each as given, and when it was really in force on simulated time.

use crate::health::{Outage, Sensor};
use crate::link::RobotLink;
use crate::sim::{FaultKind, FaultRecord};
use serde::Serialize;

/// One injected fault and when it was in force.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FaultWindow {
    pub kind: FaultKind,
    /// As it is written on the command line, e.g. `camera@60+20`, `slip@30+10:0.5`.
    pub spec: String,
    /// When it began, simulated seconds to the millisecond; null when the run ended
    /// before it did.
    pub start_s: Option<f64>,
    /// When it ended (its time ran out, or `:fault clear`); null when it was still in
    /// force as the run ended, or never began.
    pub end_s: Option<f64>,
}

impl FaultWindow {
    pub fn of(record: &FaultRecord) -> Self {
        // + 0.0: a time that rounds to zero shows no sign.
        let ms = |t: f64| (t * 1000.0).round() / 1000.0 + 0.0;
        Self {
            kind: record.spec.kind,
            spec: record.spec.to_string(),
            start_s: record.began.map(ms),
            end_s: record.ended.map(ms),
        }
    }
}

/// Every fault injected into the twin behind `link`, in the order asked; none without one.
pub fn fault_windows(link: &dyn RobotLink) -> Vec<FaultWindow> {
    link.faults().map_or(Vec::new(), |f| {
        f.records().iter().map(FaultWindow::of).collect()
    })
}

/// The windows as a person reads them, one line: "faults camera@60+20 (60.0-80.0 s)".
pub fn human(windows: &[FaultWindow]) -> Option<String> {
    if windows.is_empty() {
        return None;
    }
    let each: Vec<String> = (windows.iter())
        .map(|w| match (w.start_s, w.end_s) {
            (None, _) => format!("{} (never began)", w.spec),
            (Some(a), Some(b)) => format!("{} ({a:.1}-{b:.1} s)", w.spec),
            (Some(a), None) => format!("{} ({a:.1} s to the end)", w.spec),
        })
        .collect();
    Some(format!("faults {}", each.join(", ")))
}

/// One time a sensor was lost, as the pilot saw it, and how long after its fault ended it
/// was back.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Degradation {
    pub sensor: Sensor,
    /// When the pilot declared it lost, and when usable data came again (null: never
    /// within the run), session seconds to the millisecond.
    pub lost_s: f64,
    pub recovered_s: Option<f64>,
    /// Seconds from the end of the fault that silenced it to its recovery, when both are
    /// known.
    pub recovered_after_fault_s: Option<f64>,
}

/// The sensor each fault kind silences; none for a wheel slip, which silences nothing.
fn silenced(kind: FaultKind) -> Option<Sensor> {
    match kind {
        FaultKind::Camera => Some(Sensor::Camera),
        FaultKind::Lidar => Some(Sensor::Lidar),
        FaultKind::Odom => Some(Sensor::Odometry),
        FaultKind::Arm => Some(Sensor::Arm),
        FaultKind::Slip => None,
    }
}

/// The pilot's outages, each with the recovery after the latest fault of its sensor's kind
/// that began before it was declared lost.
pub fn degradations(outages: &[Outage], windows: &[FaultWindow]) -> Vec<Degradation> {
    // + 0.0: a time that rounds to zero shows no sign.
    let ms = |t: f64| (t * 1000.0).round() / 1000.0 + 0.0;
    (outages.iter())
        .map(|o| {
            let fault_end = (windows.iter())
                .filter(|w| silenced(w.kind) == Some(o.sensor))
                .filter(|w| w.start_s.is_some_and(|s| s <= o.lost_at))
                .filter_map(|w| w.end_s)
                .reduce(f64::max);
            Degradation {
                sensor: o.sensor,
                lost_s: ms(o.lost_at),
                recovered_s: o.recovered_at.map(ms),
                recovered_after_fault_s: o
                    .recovered_at
                    .zip(fault_end)
                    .map(|(back, end)| ms(back - end)),
            }
        })
        .collect()
}

/// The outages as a person reads them, one line: "degraded camera 61.0-80.3 s".
pub fn human_degradations(all: &[Degradation]) -> Option<String> {
    if all.is_empty() {
        return None;
    }
    let each: Vec<String> = (all.iter())
        .map(|d| match d.recovered_s {
            Some(back) => format!("{} {:.1}-{back:.1} s", d.sensor, d.lost_s),
            None => format!("{} from {:.1} s", d.sensor, d.lost_s),
        })
        .collect();
    Some(format!("degraded {}", each.join(", ")))
}

/// The faults a run's twin had injected and what the pilot lost with them, as every
/// run's JSON gives them (`faults`, `degraded`; each left out when empty).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct FaultFigures {
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub faults: Vec<FaultWindow>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub degraded: Vec<Degradation>,
}

impl FaultFigures {
    pub fn of(link: &dyn RobotLink, pilot: &crate::pilot::Pilot) -> Self {
        let faults = fault_windows(link);
        let degraded = degradations(pilot.sensor_health().outages(), &faults);
        Self { faults, degraded }
    }

    /// The lines a person reads: the faults, then what degraded; empty when neither.
    pub fn human(&self) -> String {
        let lines = [human(&self.faults), human_degradations(&self.degraded)];
        lines.into_iter().flatten().map(|l| l + "\n").collect()
    }
}
