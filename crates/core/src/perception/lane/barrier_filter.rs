//! The barrier's state from frame to frame: a discrete Bayes filter over down, moving and
//! up with seed 000 §3.2.3's transition model.
//!
//! The seed's update multiplies every state's prior by one likelihood (that of the
//! observed state matching the current one), which cancels when normalised: its posterior
//! is always the transition row of the current state, whatever was seen. Here the belief is
//! predicted through the transition matrix and then weighed by each state's own likelihood
//! of the observation (Thrun, Burgard & Fox, Probabilistic Robotics, table 4.1).

use crate::data::BarrierState;

/// Index of a state in a belief: down, moving, up (the order `BarrierSeen::belief` uses).
pub fn index(s: BarrierState) -> usize {
    match s {
        BarrierState::Down => 0,
        BarrierState::Moving => 1,
        BarrierState::Up => 2,
    }
}

/// seed 000 §3.2.3 `transition_model`, rows from, columns to (down, moving, up):
/// UP -> UP 0.95, MOVING 0.05; MOVING -> UP 0.3, MOVING 0.4, DOWN 0.3; DOWN -> DOWN 0.95,
/// MOVING 0.05.
pub const TRANSITION: [[f64; 3]; 3] = [[0.95, 0.05, 0.0], [0.3, 0.4, 0.3], [0.0, 0.05, 0.95]];

/// The belief before any barrier has been seen.
const UNIFORM: [f64; 3] = [1.0 / 3.0; 3];

/// Belief over the barrier's state.
#[derive(Clone, Debug, PartialEq)]
pub struct BarrierFilter {
    belief: [f64; 3],
    unseen: usize,
    forget_after: usize,
    tracking: bool,
}

impl BarrierFilter {
    /// A filter that forgets the barrier after `forget_after` frames without it.
    pub fn new(forget_after: usize) -> Self {
        Self {
            belief: UNIFORM,
            unseen: 0,
            forget_after,
            tracking: false,
        }
    }

    pub fn belief(&self) -> [f64; 3] {
        self.belief
    }

    /// The most probable state.
    pub fn state(&self) -> BarrierState {
        let i = (0..3).max_by(|&a, &b| self.belief[a].total_cmp(&self.belief[b]));
        BarrierState::ALL[i.unwrap_or(0)]
    }

    /// Prediction: belief'(j) = sum_i T(i, j) belief(i), i.e. T^T belief.
    pub fn predict(&mut self) {
        let b = self.belief;
        self.belief = [0, 1, 2].map(|j| (0..3).map(|i| TRANSITION[i][j] * b[i]).sum());
    }

    /// Measurement update with a confusion model: the observed state has likelihood `c`
    /// (the detection's confidence), each other state (1 - c) / 2; then normalised.
    pub fn update(&mut self, observed: BarrierState, confidence: f64) {
        let c = confidence.clamp(0.0, 1.0);
        let seen = index(observed);
        let weighed =
            [0, 1, 2].map(|i| self.belief[i] * if i == seen { c } else { (1.0 - c) / 2.0 });
        let total: f64 = weighed.iter().sum();
        // A belief the observation rules out wholly (it cannot be, with c < 1) restarts.
        self.belief = if total > 1e-300 {
            weighed.map(|w| w / total)
        } else {
            UNIFORM
        };
    }

    /// One frame: predict, then update with what was seen, if anything. Returns the belief
    /// while the barrier is tracked; after `forget_after` frames unseen it is forgotten.
    pub fn step(&mut self, observed: Option<(BarrierState, f64)>) -> Option<[f64; 3]> {
        match observed {
            Some((state, confidence)) => {
                self.predict();
                self.update(state, confidence);
                self.unseen = 0;
                self.tracking = true;
            }
            None if self.tracking => {
                self.predict();
                self.unseen += 1;
                if self.unseen >= self.forget_after {
                    self.reset();
                }
            }
            None => {}
        }
        self.tracking.then_some(self.belief)
    }

    pub fn reset(&mut self) {
        *self = Self::new(self.forget_after);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use BarrierState::{Down, Up};

    fn close(a: [f64; 3], b: [f64; 3]) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-4)
    }

    /// seed 000 §3.2.3's `update_state` as listed: prior = the current state's transition
    /// row, every entry times one likelihood, normalised, MAP taken.
    fn seed_update(current: BarrierState, observed: BarrierState, c: f64) -> BarrierState {
        let likelihood = if observed == current { c } else { 1.0 - c };
        let row = TRANSITION[index(current)];
        let posterior = row.map(|p| p * likelihood);
        let total: f64 = posterior.iter().sum();
        let p = posterior.map(|p| p / total);
        BarrierState::ALL[(0..3).max_by(|&a, &b| p[a].total_cmp(&p[b])).unwrap()]
    }

    #[test]
    fn one_step_matches_the_hand_worked_numbers() {
        let mut f = BarrierFilter::new(10);
        // Predict from uniform: down (0.95 + 0.3) / 3, moving (0.05 + 0.4 + 0.05) / 3, up
        // (0.3 + 0.95) / 3 = 0.41667, 0.16667, 0.41667.
        f.predict();
        assert!(
            close(f.belief(), [0.41667, 0.16667, 0.41667]),
            "{:?}",
            f.belief()
        );
        // UP seen with c = 0.8: 0.41667 * 0.1, 0.16667 * 0.1, 0.41667 * 0.8 = 0.041667,
        // 0.016667, 0.333333, sum 0.391667 -> 0.10638, 0.04255, 0.85106.
        f.update(Up, 0.8);
        assert!(
            close(f.belief(), [0.10638, 0.04255, 0.85106]),
            "{:?}",
            f.belief()
        );
        assert_eq!(f.state(), Up);
    }

    #[test]
    fn the_seeds_update_never_moves_but_this_one_follows_the_arm_down() {
        // The seed's: sure it is up, it stays up however often the arm is seen down.
        let mut seed = Up;
        for _ in 0..50 {
            seed = seed_update(seed, Down, 0.99);
        }
        assert_eq!(seed, Up);
        // This filter: from up it must pass through moving (T(up, down) = 0), and does.
        let mut f = BarrierFilter::new(10);
        f.step(Some((Up, 0.9)));
        for _ in 0..5 {
            f.step(Some((Up, 0.9)));
        }
        assert_eq!(f.state(), Up);
        // Predict [0, 0.05, 0.95] from certainty; with the arm seen down at 0.9 the first
        // frame gives down 0 (it cannot jump), the next ones carry it through.
        let mut states = Vec::new();
        for _ in 0..6 {
            f.step(Some((Down, 0.9)));
            states.push(f.state());
        }
        assert_eq!(states.last(), Some(&Down), "{states:?}");
        assert!(states.len() >= 2 && states[0] == Up, "{states:?}");
    }

    #[test]
    fn an_unseen_barrier_keeps_the_prediction_then_is_forgotten() {
        let mut f = BarrierFilter::new(3);
        assert_eq!(f.step(None), None);
        let seen = f.step(Some((Down, 0.8))).unwrap();
        // One frame unseen: the belief is the prediction alone, T^T seen.
        let predicted: [f64; 3] =
            [0, 1, 2].map(|j| (0..3).map(|i| TRANSITION[i][j] * seen[i]).sum());
        assert!(close(f.step(None).unwrap(), predicted));
        assert!(f.step(None).is_some());
        assert_eq!(f.step(None), None);
        assert_eq!(f.belief(), UNIFORM);
    }
}
