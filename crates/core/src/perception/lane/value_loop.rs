//! The PI loop that moves the lane masks' brightness floor so lane pixels stay near a
//! target share of the image (seed 000 §2.1.2's dynamic threshold adjustment).
//!
//! Two changes from the seed's listing, both so the loop settles: the floor drops when too
//! few pixels pass (the listing adds `Kp e + Ki sum(e)` with `e = target - ratio`, which
//! raises the floor when pixels are already too few), and the correction is the PI law's
//! output about the starting floor rather than added to the floor each frame (which, with
//! the integral, would integrate twice). The integral stops while the floor sits at a bound.
//!
//! And one addition: cells that make no lane line are not lane pixels. A frame in which
//! neither line is found counts as one with none (unless it has more than the band's most,
//! which is clutter), so a floor learnt in the light sinks until paint under a shadow
//! passes again, rather than holding the robot stopped before a lane it cannot see.

/// The brightness floor and the loop's state.
#[derive(Clone, Debug, PartialEq)]
pub struct ValueLoop {
    start: f64,
    bounds: [f64; 2],
    /// The share of lane pixels held: [least, most].
    band: [f64; 2],
    gains: [f64; 2],
    integral: f64,
    floor: f64,
}

impl ValueLoop {
    /// A loop holding `target` (a fraction of the image) from floor `start`, within
    /// `bounds`, with gains [Kp, Ki] in brightness levels per unit of ratio.
    pub fn new(start: f64, bounds: [f64; 2], band: [f64; 2], gains: [f64; 2]) -> Self {
        Self {
            start,
            bounds,
            band,
            gains,
            integral: 0.0,
            floor: start.clamp(bounds[0], bounds[1]),
        }
    }

    /// The brightness floor for the next frame.
    pub fn floor(&self) -> f64 {
        self.floor
    }

    /// Takes the share of lane pixels the last frame had, and whether they made a lane
    /// line, and moves the floor.
    pub fn update(&mut self, pixel_ratio: f64, line_found: bool) -> f64 {
        let [least, most] = self.band;
        let pixel_ratio = if line_found || pixel_ratio > most {
            pixel_ratio
        } else {
            0.0
        };
        // seed 000 §2.1.2: error = target - ratio; adjustment = Kp e + Ki sum(e). Within the
        // band the error is nought: the floor holds rather than cut into the paint.
        let error = if pixel_ratio < least {
            least - pixel_ratio
        } else if pixel_ratio > most {
            most - pixel_ratio
        } else {
            0.0
        };
        let [kp, ki] = self.gains;
        let [lo, hi] = self.bounds;
        let trial = self.integral + error;
        let unclamped = self.start - (kp * error + ki * trial);
        self.floor = unclamped.clamp(lo, hi);
        // Anti-windup (Astrom & Murray 10.4): keep the sum only while the floor is free.
        if unclamped == self.floor {
            self.integral = trial;
        }
        self.floor
    }

    pub fn reset(&mut self) {
        self.integral = 0.0;
        self.floor = self.start.clamp(self.bounds[0], self.bounds[1]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn too_few_pixels_lower_the_floor_and_too_many_raise_it() {
        let mut l = ValueLoop::new(100.0, [60.0, 200.0], [0.025, 0.025], [1000.0, 200.0]);
        // No pixels: e = 0.025, floor = 100 - (25 + 5) = 70, then 100 - (25 + 10) = 65.
        assert!((l.update(0.0, true) - 70.0).abs() < 1e-9);
        assert!((l.update(0.0, true) - 65.0).abs() < 1e-9);
        // At the bound the sum stops growing, so the floor comes straight back up.
        for _ in 0..10 {
            l.update(0.0, true);
        }
        assert_eq!(l.floor(), 60.0);
        // The sum stopped at 0.075 (the frame that reached 60 exactly): on target the floor
        // is 100 - 200 * 0.075 = 85 at once, not held down by a wound-up sum.
        assert!((l.update(0.025, true) - 85.0).abs() < 1e-9, "{}", l.floor());
        let mut up = ValueLoop::new(100.0, [60.0, 200.0], [0.025, 0.025], [1000.0, 200.0]);
        // 5 % of the image: e = -0.025, floor = 100 + 25 + 5 = 130.
        assert!((up.update(0.05, true) - 130.0).abs() < 1e-9);
        // On target the floor holds what the sum has learnt.
        assert!((up.update(0.025, true) - 105.0).abs() < 1e-9);
    }

    #[test]
    fn cells_that_make_no_line_lower_the_floor_and_clutter_still_raises_it() {
        let band = [0.01, 0.10];
        let mut l = ValueLoop::new(100.0, [30.0, 200.0], band, [100.0, 200.0]);
        // 3 % of the view passes, in the band, but makes no line: counted as none.
        let first = l.update(0.03, false);
        assert!(first < 100.0, "{first}");
        for _ in 0..20 {
            l.update(0.03, false);
        }
        assert!(l.floor() < first - 20.0, "{}", l.floor());
        // The same share making a line holds the floor where it is (less the last frame's
        // proportional kick).
        let held = l.update(0.03, true);
        assert_eq!(l.update(0.03, true), held);
        assert!(held < first - 20.0, "{held}");
        // Clutter over the band's most raises the floor whether or not a line is found.
        assert!(l.update(0.2, false) > held);
    }
}
