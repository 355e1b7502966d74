//! One lane line from frame to frame: a new fit is checked against the physical limits
//! and the last filtered fit (seed 000 §2.2.1's validation), then averaged with the last
//! few, weighted by their confidence (§2.3.2).

use super::windows::{LineFound, x_at};
use std::collections::VecDeque;

/// The signed curvature of `fit` at row `y`, 1/m, positive turning left.
/// seed 000 §2.2.1: kappa = |2a| / (1 + (2 a y + b)^2)^(3/2); rows grow towards the robot
/// and x to its right, so a line bending left ahead has a < 0.
pub fn curvature(fit: &[f64; 3], y: f64) -> f64 {
    let [a, b, _] = *fit;
    let slope = 2.0 * a * y + b;
    -2.0 * a / (1.0 + slope * slope).powf(1.5) * 1000.0
}

/// What a line's fit must respect to be taken.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitLimits {
    /// Most |curvature| anywhere in the view, 1/m.
    pub max_curvature: f64,
    /// Most sideways change from the filtered fit anywhere in the view, millimetres.
    pub max_jump_mm: f64,
    /// The view's rows span 0..rows_mm.
    pub rows_mm: f64,
}

/// Why a fit was refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Refusal {
    Curvature,
    Jump,
}

impl FitLimits {
    /// seed 000 §2.2.1 `validate_lane_geometry`: excessive curvature, then a discontinuous
    /// change from the previous frame, measured as the sideways gap between the two fits
    /// at the near, middle and far rows rather than coefficient by coefficient.
    pub fn check(&self, fit: &[f64; 3], previous: Option<&[f64; 3]>) -> Result<(), Refusal> {
        let rows = [0.0, self.rows_mm / 2.0, self.rows_mm];
        if rows
            .iter()
            .any(|&y| curvature(fit, y).abs() > self.max_curvature)
        {
            return Err(Refusal::Curvature);
        }
        let jumped = |p: &[f64; 3]| {
            rows.iter()
                .any(|&y| (x_at(fit, y) - x_at(p, y)).abs() > self.max_jump_mm)
        };
        match previous {
            Some(p) if jumped(p) => Err(Refusal::Jump),
            _ => Ok(()),
        }
    }
}

/// Refusals in a row after which a jumped line is taken as the new line.
const JUMPS_TRUSTED: usize = 3;

/// One line's recent fits and their filtered value.
#[derive(Clone, Debug)]
pub struct LineTrack {
    frames: usize,
    history: VecDeque<([f64; 3], f64)>,
    misses: usize,
    jumps: usize,
    filtered: Option<[f64; 3]>,
}

impl LineTrack {
    /// A track averaging the last `frames` fits.
    pub fn new(frames: usize) -> Self {
        Self {
            frames: frames.max(1),
            history: VecDeque::new(),
            misses: 0,
            jumps: 0,
            filtered: None,
        }
    }

    /// Takes this frame's line (if one was found) and returns the filtered fit; a line
    /// missing for a whole window of frames is forgotten.
    pub fn offer(&mut self, found: Option<LineFound>, limits: &FitLimits) -> Option<[f64; 3]> {
        let taken = found.filter(
            |line| match limits.check(&line.fit, self.filtered.as_ref()) {
                Ok(()) => true,
                Err(Refusal::Jump) if self.jumps + 1 >= JUMPS_TRUSTED => {
                    // The line has moved for good (or the old one was wrong): start again.
                    self.history.clear();
                    true
                }
                Err(Refusal::Jump) => {
                    self.jumps += 1;
                    false
                }
                Err(Refusal::Curvature) => false,
            },
        );
        match taken {
            Some(line) => {
                self.jumps = 0;
                self.misses = 0;
                self.history
                    .push_back((line.fit, line.confidence.max(1e-6)));
                while self.history.len() > self.frames {
                    self.history.pop_front();
                }
            }
            None => {
                self.misses += 1;
                if self.misses >= self.frames {
                    self.history.clear();
                    self.jumps = 0;
                }
            }
        }
        self.filtered = weighted_mean(&self.history);
        self.filtered
    }

    pub fn filtered(&self) -> Option<[f64; 3]> {
        self.filtered
    }

    pub fn reset(&mut self) {
        *self = Self::new(self.frames);
    }
}

/// seed 000 §2.3.2 `TemporalLaneFilter`: coefficients averaged with weights = confidence /
/// sum of confidences.
fn weighted_mean(history: &VecDeque<([f64; 3], f64)>) -> Option<[f64; 3]> {
    let total: f64 = history.iter().map(|h| h.1).sum();
    (total > 0.0).then(|| {
        let mut m = [0.0; 3];
        for (fit, w) in history {
            for (mi, fi) in m.iter_mut().zip(fit) {
                *mi += fi * w / total;
            }
        }
        m
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const LIMITS: FitLimits = FitLimits {
        max_curvature: 5.0,
        max_jump_mm: 80.0,
        rows_mm: 700.0,
    };

    fn line(c: f64, confidence: f64) -> Option<LineFound> {
        Some(LineFound {
            fit: [0.0, 0.0, c],
            confidence,
        })
    }

    #[test]
    fn a_line_bending_left_has_positive_curvature() {
        // x = -0.0005 y^2 (mm): a = -5e-4 /mm, so kappa = 1e-3 /mm = 1 /m at the vertex.
        let k = curvature(&[-0.0005, 0.0, 0.0], 0.0);
        assert!((k - 1.0).abs() < 1e-12, "{k}");
        assert!(curvature(&[0.0005, 0.2, 0.0], 100.0) < 0.0);
    }

    #[test]
    fn fits_are_averaged_by_confidence_and_jumps_are_refused() {
        let mut t = LineTrack::new(5);
        t.offer(line(300.0, 1.0), &LIMITS);
        // (300 * 1 + 330 * 0.5) / 1.5 = 310.
        let f = t.offer(line(330.0, 0.5), &LIMITS).unwrap();
        assert!((f[2] - 310.0).abs() < 1e-9, "{f:?}");
        // 200 mm away: refused twice, taken the third time as the line's new place.
        assert_eq!(t.offer(line(510.0, 1.0), &LIMITS).unwrap()[2], f[2]);
        assert_eq!(t.offer(line(510.0, 1.0), &LIMITS).unwrap()[2], f[2]);
        assert_eq!(t.offer(line(510.0, 1.0), &LIMITS).unwrap()[2], 510.0);
        // Too tight a bend (radius 0.1 m) is never taken.
        let tight = LineFound {
            fit: [-0.005, 0.0, 510.0],
            confidence: 1.0,
        };
        assert_eq!(t.offer(Some(tight), &LIMITS).unwrap()[2], 510.0);
        // Five frames without the line (the refused bend is one) and it is forgotten.
        for _ in 0..3 {
            assert!(t.offer(None, &LIMITS).is_some());
        }
        assert_eq!(t.offer(None, &LIMITS), None);
    }
}
