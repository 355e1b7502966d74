//! The arbiter (seed 000 §5.3.1): every behaviour proposes a command or abstains each
//! tick; the highest-priority active proposal is sent. A change of winner is a
//! transition, logged once and kept (the last 100, as the seed's `behavior_history`). A
//! behaviour may be switched off, for a while or until switched on again (the seed's
//! `activate_behavior(name, duration)` timer); the e-stop never is.

use super::table::Behaviour;
use navdeck_core::geometry::Twist;
use std::collections::{BTreeMap, VecDeque};

/// Transitions kept (seed 000 §5.3.1: `deque(maxlen=100)`).
pub const HISTORY: usize = 100;

/// What a behaviour asks for this tick, and why.
#[derive(Clone, Debug, PartialEq)]
pub struct Proposal {
    pub behaviour: Behaviour,
    pub twist: Twist,
    pub reason: String,
}

impl Proposal {
    pub fn new(behaviour: Behaviour, twist: Twist, reason: impl Into<String>) -> Self {
        let reason = reason.into();
        Self {
            behaviour,
            twist,
            reason,
        }
    }
}

/// A change of the winning behaviour.
#[derive(Clone, Debug, PartialEq)]
pub struct Transition {
    pub t: f64,
    pub from: Option<Behaviour>,
    pub to: Option<Behaviour>,
    /// Why the new winner acts (its proposal's reason), or why none does.
    pub reason: String,
}

impl Transition {
    /// One line for the log: "collision monitor (was teleop): stopping, obstacle ...".
    pub fn text(&self) -> String {
        let name = |b: Option<Behaviour>| b.map_or("idle".to_string(), |b| b.to_string());
        let mut text = format!("behaviour: {} (was {})", name(self.to), name(self.from));
        if !self.reason.is_empty() {
            text.push_str(": ");
            text.push_str(&self.reason);
        }
        text
    }
}

/// See the module comment.
#[derive(Clone, Debug, Default)]
pub struct Arbiter {
    /// Behaviours switched off, and until when (None: until switched on).
    off: BTreeMap<Behaviour, Option<f64>>,
    winner: Option<Behaviour>,
    reason: String,
    history: VecDeque<Transition>,
}

impl Arbiter {
    /// The command for `t` from `proposals`: the active one of highest priority (the
    /// first listed among equals), or zero when none is. Returns the transition when the
    /// winner changed.
    pub fn arbitrate(&mut self, t: f64, proposals: &[Proposal]) -> (Twist, Option<Transition>) {
        self.off.retain(|_, until| until.is_none_or(|u| t < u));
        let best = (proposals.iter()).filter(|p| self.is_on(p.behaviour)).fold(
            None::<&Proposal>,
            |best, p| match best {
                Some(b) if b.behaviour.priority() >= p.behaviour.priority() => Some(b),
                _ => Some(p),
            },
        );
        let (to, twist, reason) = match best {
            Some(p) => (Some(p.behaviour), p.twist, p.reason.clone()),
            None => (None, Twist::ZERO, String::new()),
        };
        let changed = to != self.winner;
        let transition = changed.then(|| Transition {
            t,
            from: self.winner,
            to,
            reason: reason.clone(),
        });
        if let Some(tr) = &transition {
            if self.history.len() == HISTORY {
                self.history.pop_front();
            }
            self.history.push_back(tr.clone());
        }
        self.winner = to;
        self.reason = reason;
        (twist, transition)
    }

    /// Switches `behaviour` off at `t`, for `seconds` or until switched on; the e-stop
    /// cannot be.
    pub fn switch_off(
        &mut self,
        behaviour: Behaviour,
        t: f64,
        seconds: Option<f64>,
    ) -> Result<(), String> {
        if behaviour == Behaviour::EmergencyStop {
            return Err("the e-stop cannot be switched off".into());
        }
        if let Some(s) = seconds
            && !(s.is_finite() && s > 0.0)
        {
            return Err(format!("{s} s: a time to switch off must be positive"));
        }
        self.off.insert(behaviour, seconds.map(|s| t + s));
        Ok(())
    }

    pub fn switch_on(&mut self, behaviour: Behaviour) {
        self.off.remove(&behaviour);
    }

    /// Whether `behaviour` may win (not switched off).
    pub fn is_on(&self, behaviour: Behaviour) -> bool {
        !self.off.contains_key(&behaviour)
    }

    /// When a switched-off behaviour comes back on by itself (None: it stays off).
    pub fn off_until(&self, behaviour: Behaviour) -> Option<Option<f64>> {
        self.off.get(&behaviour).copied()
    }

    /// The behaviour whose command went out last, and why.
    pub fn winner(&self) -> Option<(Behaviour, &str)> {
        self.winner.map(|b| (b, self.reason.as_str()))
    }

    /// The last `HISTORY` transitions, oldest first.
    pub fn history(&self) -> impl DoubleEndedIterator<Item = &Transition> {
        self.history.iter()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use Behaviour::*;

    fn drive(v: f64) -> Twist {
        Twist {
            linear: v,
            angular: 0.0,
        }
    }

    fn propose(b: Behaviour, v: f64) -> Proposal {
        Proposal::new(b, drive(v), format!("{b} asks {v}"))
    }

    #[test]
    fn the_highest_priority_proposal_wins_whatever_the_order() {
        let mut a = Arbiter::default();
        let all = [
            propose(Exploration, 0.1),
            propose(CollisionMonitor, 0.05),
            propose(Teleop, 0.2),
            propose(PathFollowing, 0.15),
        ];
        assert_eq!(a.arbitrate(0.0, &all).0, drive(0.05));
        let mut reversed = all.clone();
        reversed.reverse();
        assert_eq!(a.arbitrate(0.1, &reversed).0, drive(0.05));
        // Without the monitor, teleop overrides both autonomous behaviours.
        assert_eq!(a.arbitrate(0.2, &all[2..]).0, drive(0.2));
        assert_eq!(
            a.arbitrate(0.3, &[all[0].clone(), all[3].clone()]).0,
            drive(0.15)
        );
        // The e-stop beats everything.
        let mut stopped = all.to_vec();
        stopped.push(propose(EmergencyStop, 0.0));
        assert_eq!(a.arbitrate(0.4, &stopped).0, drive(0.0));
        assert_eq!(a.winner().map(|w| w.0), Some(EmergencyStop));
    }

    #[test]
    fn nobody_proposing_means_stop_and_idle() {
        let mut a = Arbiter::default();
        a.arbitrate(0.0, &[propose(Teleop, 0.2)]);
        let (twist, tr) = a.arbitrate(0.1, &[]);
        assert_eq!(twist, Twist::ZERO);
        assert_eq!(tr.unwrap().to, None);
        assert_eq!(a.winner(), None);
    }

    #[test]
    fn a_transition_is_recorded_once_per_change_and_the_last_hundred_kept() {
        let mut a = Arbiter::default();
        let (_, first) = a.arbitrate(0.0, &[propose(Teleop, 0.2)]);
        assert_eq!(
            first.unwrap().text(),
            "behaviour: teleop (was idle): teleop asks 0.2"
        );
        // Held keys repeat: no new transition.
        for k in 1..50 {
            assert_eq!(a.arbitrate(k as f64 * 0.1, &[propose(Teleop, 0.2)]).1, None);
        }
        assert_eq!(a.history().count(), 1);
        for k in 0..150 {
            let b = if k % 2 == 0 { CollisionMonitor } else { Teleop };
            a.arbitrate(10.0 + k as f64, &[propose(Teleop, 0.2), propose(b, 0.0)]);
        }
        assert_eq!(a.history().count(), HISTORY);
        assert_eq!(a.history().last().unwrap().t, 159.0);
    }

    #[test]
    fn a_behaviour_switched_off_for_a_while_comes_back() {
        let mut a = Arbiter::default();
        let both = [propose(Teleop, 0.2), propose(CollisionMonitor, 0.0)];
        a.switch_off(CollisionMonitor, 0.0, Some(5.0)).unwrap();
        assert_eq!(a.arbitrate(1.0, &both).0, drive(0.2));
        assert_eq!(a.arbitrate(5.0, &both).0, drive(0.0));
        a.switch_off(CollisionMonitor, 6.0, None).unwrap();
        assert_eq!(a.arbitrate(1000.0, &both).0, drive(0.2));
        a.switch_on(CollisionMonitor);
        assert_eq!(a.arbitrate(1001.0, &both).0, drive(0.0));
        assert!(a.switch_off(EmergencyStop, 0.0, None).is_err());
        assert!(a.switch_off(Teleop, 0.0, Some(-1.0)).is_err());
    }
}
