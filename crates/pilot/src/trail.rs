//! Where the robot has driven: its estimated position, a point every few centimetres,
//! for the map's trail.

use navdeck_core::geometry::Point2;

/// A new point after the estimate moved this far, metres.
const STEP: f64 = 0.03;
/// Points kept; past this the older half goes (at 3 cm apart, the last 300 m or more).
const KEPT: usize = 20_000;

#[derive(Clone, Debug, Default)]
pub struct Trail {
    points: Vec<Point2>,
}

impl Trail {
    /// Notes the robot at `here`.
    pub fn note(&mut self, here: Point2) {
        if self.points.last().is_some_and(|p| p.distance(here) < STEP) {
            return;
        }
        if self.points.len() >= KEPT {
            self.points.drain(..KEPT / 2);
        }
        self.points.push(here);
    }

    /// Oldest first.
    pub fn points(&self) -> &[Point2] {
        &self.points
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_every_step_and_the_oldest_half_goes_when_full() {
        let mut trail = Trail::default();
        for i in 0..10 {
            trail.note(Point2::new(i as f64 * 0.01, 0.0));
        }
        // 0, 0.03, 0.06, 0.09.
        assert_eq!(trail.points().len(), 4);
        for i in 0..KEPT + 10 {
            trail.note(Point2::new(1.0 + i as f64 * STEP * 1.01, 0.0));
        }
        assert!(trail.points().len() <= KEPT);
        let newest = trail.points().last().unwrap().x;
        assert!((newest - (1.0 + (KEPT + 9) as f64 * STEP * 1.01)).abs() < 1e-9);
    }
}
