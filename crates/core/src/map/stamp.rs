//! What one landmark (or the wall between two) costs around it: seed 001 section 4's
//! inflated region at 0.7, a lethal core inside it and a falling gradient outside.

use super::costmap::{INFLATED, LETHAL};
use crate::geometry::{Point2, Segment};

/// The shape a stamp is measured from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    Disc(Point2),
    Wall(Point2, Point2),
}

/// Radii of the cost rings around a shape, metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rings {
    pub lethal: f64,
    pub inflated: f64,
    pub gradient: f64,
}

impl Rings {
    /// How far the stamp reaches.
    pub fn reach(&self) -> f64 {
        self.inflated.max(self.lethal) + self.gradient
    }

    /// Cost at squared distance `d2` from the shape: a square root only in the gradient band.
    pub fn cost_at_squared(&self, d2: f64) -> u8 {
        if d2 <= self.lethal * self.lethal {
            LETHAL
        } else if d2 <= self.inflated * self.inflated {
            INFLATED
        } else {
            let reach = self.inflated + self.gradient;
            if d2 < reach * reach {
                self.cost_at(d2.sqrt())
            } else {
                0
            }
        }
    }

    /// Cost at distance `d` from the shape.
    pub fn cost_at(&self, d: f64) -> u8 {
        if d <= self.lethal {
            LETHAL
        } else if d <= self.inflated {
            INFLATED
        } else if d < self.inflated + self.gradient {
            // Linear fall from just under 0.7 to zero across the gradient band.
            let fraction = 1.0 - (d - self.inflated) / self.gradient;
            (f64::from(INFLATED - 1) * fraction).ceil() as u8
        } else {
            0
        }
    }
}

/// One shape with its rings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stamp {
    pub shape: Shape,
    pub rings: Rings,
}

impl Stamp {
    /// Squared distance from `p` to the shape (the segment's projection clamped to its ends).
    pub fn distance_squared(&self, p: Point2) -> f64 {
        match self.shape {
            Shape::Disc(c) => Segment::new(c, c).distance_squared_to(p),
            Shape::Wall(a, b) => Segment::new(a, b).distance_squared_to(p),
        }
    }

    /// The world rectangle (x0, y0, x1, y1) outside which the stamp costs nothing.
    pub fn bounds(&self) -> (f64, f64, f64, f64) {
        let r = self.rings.reach();
        let (a, b) = match self.shape {
            Shape::Disc(c) => (c, c),
            Shape::Wall(a, b) => (a, b),
        };
        (
            a.x.min(b.x) - r,
            a.y.min(b.y) - r,
            a.x.max(b.x) + r,
            a.y.max(b.y) + r,
        )
    }

    pub fn cost_at(&self, p: Point2) -> u8 {
        self.rings.cost_at_squared(self.distance_squared(p))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const RINGS: Rings = Rings {
        lethal: 0.15,
        inflated: 0.30,
        gradient: 0.20,
    };

    #[test]
    fn rings_follow_seed_001_values() {
        assert_eq!(RINGS.cost_at(0.0), LETHAL);
        assert_eq!(RINGS.cost_at(0.2), INFLATED);
        assert_eq!(RINGS.cost_at(0.30), INFLATED);
        let half = RINGS.cost_at(0.40);
        assert!(half > 30 && half < 40, "{half}");
        assert_eq!(RINGS.cost_at(0.5), 0);
    }

    #[test]
    fn wall_stamp_measures_from_the_segment() {
        let s = Stamp {
            shape: Shape::Wall(Point2::new(0.0, 0.0), Point2::new(1.0, 0.0)),
            rings: RINGS,
        };
        assert_eq!(s.cost_at(Point2::new(0.5, 0.1)), LETHAL);
        assert_eq!(s.cost_at(Point2::new(0.5, 0.6)), 0);
        let (x0, y0, x1, y1) = s.bounds();
        assert!((x0 + 0.5).abs() < 1e-9 && (y1 - 0.5).abs() < 1e-9 && x1 > 1.4 && y0 < -0.4);
    }
}
