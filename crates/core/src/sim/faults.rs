//! The twin's fault schedule: the faults asked for (`--fault`, `:fault`), when each really
//! began and ended in simulated time, which are in force now, and a line for the log as
//! each begins and ends. The twin moves it on every physics step (`advance`); nothing
//! here reads a clock.

use super::fault::{FaultKind, FaultSpec};

/// One fault asked for, and when it was in force (simulated seconds, whole physics steps).
#[derive(Clone, Debug, PartialEq)]
pub struct FaultRecord {
    pub spec: FaultSpec,
    /// When it began; `None` while it has not.
    pub began: Option<f64>,
    /// When it ended (its time ran out, or `:fault clear`); `None` while it has not.
    pub ended: Option<f64>,
}

impl FaultRecord {
    /// Whether it is in force now.
    pub fn in_force(&self) -> bool {
        self.began.is_some() && self.ended.is_none()
    }
}

/// A fault beginning or ending, for the log.
#[derive(Clone, Debug, PartialEq)]
pub struct FaultNote {
    /// Simulated seconds.
    pub time: f64,
    /// True as it begins, false as it ends.
    pub began: bool,
    /// "fault injected: camera dark for 20 s", "fault cleared: camera".
    pub text: String,
}

/// How a newly asked fault stands.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scheduled {
    /// In force from now.
    Now,
    /// It begins at this simulated time.
    Later(f64),
    /// Its time is over already: nothing was scheduled.
    Past,
}

/// The faults asked for, in the order asked, and the simulated time they were last moved
/// on to.
#[derive(Clone, Debug, Default)]
pub struct Faults {
    records: Vec<FaultRecord>,
    now: f64,
    notes: Vec<FaultNote>,
}

impl Faults {
    /// Simulated seconds the schedule was last moved on to: the twin's time.
    pub fn now(&self) -> f64 {
        self.now
    }

    /// Every fault asked for, with when it was in force.
    pub fn records(&self) -> &[FaultRecord] {
        &self.records
    }

    /// The faults in force now.
    pub fn active(&self) -> impl Iterator<Item = &FaultSpec> {
        self.records
            .iter()
            .filter(|r| r.in_force())
            .map(|r| &r.spec)
    }

    /// Whether a fault of `kind` is in force now.
    pub fn is_active(&self, kind: FaultKind) -> bool {
        self.active().any(|s| s.kind == kind)
    }

    /// The kinds in force now, each once, in the order of `FaultKind::ALL`.
    pub fn active_kinds(&self) -> Vec<FaultKind> {
        let mut kinds: Vec<FaultKind> = self.active().map(|s| s.kind).collect();
        kinds.sort_unstable();
        kinds.dedup();
        kinds
    }

    /// The share of the commanded travel the wheels deliver now: the least of the slips
    /// in force, `None` when none is.
    pub fn slip_ratio(&self) -> Option<f64> {
        (self.active())
            .filter_map(|s| s.slip_ratio)
            .reduce(f64::min)
    }

    /// When the latest fault of `kind` ended, if one did.
    pub fn last_ended(&self, kind: FaultKind) -> Option<f64> {
        (self.records.iter())
            .filter(|r| r.spec.kind == kind)
            .filter_map(|r| r.ended)
            .reduce(f64::max)
    }

    /// Adds `spec` (its times in simulated seconds); one whose time has begun is in force
    /// at once. One whose time is over already is not added.
    pub fn schedule(&mut self, spec: FaultSpec) -> Scheduled {
        if spec.end_s().is_some_and(|end| end <= self.now) {
            return Scheduled::Past;
        }
        self.records.push(FaultRecord {
            spec,
            began: None,
            ended: None,
        });
        self.advance(self.now);
        if spec.start_s <= self.now {
            Scheduled::Now
        } else {
            Scheduled::Later(spec.start_s)
        }
    }

    /// Ends every fault in force now and forgets those not yet begun; returns how many
    /// were in force and how many were forgotten.
    pub fn clear(&mut self) -> (usize, usize) {
        let now = self.now;
        let asked = self.records.len();
        self.records.retain(|r| r.began.is_some());
        let forgotten = asked - self.records.len();
        let mut ended = 0;
        for r in self.records.iter_mut().filter(|r| r.in_force()) {
            r.ended = Some(now);
            self.notes.push(cleared(now, r.spec.kind));
            ended += 1;
        }
        (ended, forgotten)
    }

    /// Moves the schedule on to simulated time `now`: faults whose time has come begin,
    /// those whose time is over end, each with a note.
    pub fn advance(&mut self, now: f64) {
        self.now = now;
        for r in &mut self.records {
            match (r.began, r.ended) {
                (None, _) if r.spec.active(now) => {
                    r.began = Some(now);
                    let (effect, lasting) = (r.spec.effect(), r.spec.lasting());
                    self.notes.push(FaultNote {
                        time: now,
                        began: true,
                        text: format!("fault injected: {effect} {lasting}"),
                    });
                }
                (Some(_), None) if !r.spec.active(now) => {
                    r.ended = Some(now);
                    self.notes.push(cleared(now, r.spec.kind));
                }
                _ => {}
            }
        }
    }

    /// The notes since the last call, oldest first.
    pub fn take_notes(&mut self) -> Vec<FaultNote> {
        std::mem::take(&mut self.notes)
    }
}

fn cleared(time: f64, kind: FaultKind) -> FaultNote {
    FaultNote {
        time,
        began: false,
        text: format!("fault cleared: {kind}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(text: &str) -> FaultSpec {
        text.parse().unwrap()
    }

    fn texts(faults: &mut Faults) -> Vec<String> {
        faults.take_notes().into_iter().map(|n| n.text).collect()
    }

    #[test]
    fn a_fault_begins_and_ends_on_time_with_a_line_each() {
        let mut f = Faults::default();
        assert_eq!(f.schedule(spec("camera@1+2")), Scheduled::Later(1.0));
        f.advance(0.5);
        assert!(!f.is_active(FaultKind::Camera));
        f.advance(1.0);
        assert_eq!(f.active_kinds(), vec![FaultKind::Camera]);
        assert_eq!(texts(&mut f), ["fault injected: camera dark for 2 s"]);
        f.advance(3.0);
        assert!(!f.is_active(FaultKind::Camera));
        assert_eq!(texts(&mut f), ["fault cleared: camera"]);
        let r = &f.records()[0];
        assert_eq!((r.began, r.ended), (Some(1.0), Some(3.0)));
        assert_eq!(f.last_ended(FaultKind::Camera), Some(3.0));
    }

    #[test]
    fn a_fault_due_already_is_in_force_at_once_and_one_over_is_refused() {
        let mut f = Faults::default();
        f.advance(10.0);
        assert_eq!(f.schedule(spec("lidar@5+10")), Scheduled::Now);
        assert!(f.is_active(FaultKind::Lidar));
        assert_eq!(f.schedule(spec("odom@1+2")), Scheduled::Past);
        assert_eq!(f.records().len(), 1);
    }

    #[test]
    fn clear_ends_what_is_in_force_and_forgets_the_rest() {
        let mut f = Faults::default();
        f.schedule(spec("arm@0"));
        f.schedule(spec("slip@0+5:0.3"));
        f.schedule(spec("slip@0+5:0.6"));
        f.schedule(spec("camera@50+5"));
        assert_eq!(f.slip_ratio(), Some(0.3));
        f.take_notes();
        f.advance(2.0);
        assert_eq!(f.clear(), (3, 1));
        assert!(f.active_kinds().is_empty());
        assert_eq!(f.slip_ratio(), None);
        assert_eq!(f.records().len(), 3, "the camera's never began");
        assert_eq!(
            texts(&mut f),
            [
                "fault cleared: arm",
                "fault cleared: slip",
                "fault cleared: slip"
            ]
        );
        // Cleared is over: it does not begin again.
        f.advance(3.0);
        assert!(f.take_notes().is_empty());
    }
}
