//! The faults injected into a run's twin (`--fault`, `:fault`), as the runs' JSON lists
//! them: each as given, and when it was really in force on simulated time.

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
        let ms = |t: f64| (t * 1000.0).round() / 1000.0;
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
