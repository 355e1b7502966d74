//! A zone's shape in the robot's frame: a circle on the robot's centre or a polygon.

use super::config::PolygonConfig;
use super::outline;
use crate::geometry::Point2;

/// Where a zone reaches, in the robot's frame (x forward, y left, metres).
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// Every point within `radius` of the robot's centre.
    Circle { radius: f64 },
    /// The inside of a simple polygon; `reach` is its farthest corner from the centre.
    Polygon { corners: Vec<Point2>, reach: f64 },
}

impl Shape {
    /// The shape a zone's config gives it: its `points`, else its `radius`, else the
    /// robot's footprint, a circle of `footprint_radius`.
    pub fn of(polygon: &PolygonConfig, footprint_radius: f64) -> Shape {
        match (&polygon.points, polygon.radius) {
            (Some(points), _) => {
                let corners: Vec<Point2> = points.iter().map(|&[x, y]| Point2::new(x, y)).collect();
                let reach = corners.iter().map(|c| c.x.hypot(c.y)).fold(0.0, f64::max);
                Shape::Polygon { corners, reach }
            }
            (None, Some(radius)) => Shape::Circle { radius },
            (None, None) => Shape::Circle {
                radius: footprint_radius,
            },
        }
    }

    /// True when `p` (robot frame) lies inside; a point that is not finite never does.
    pub fn contains(&self, p: Point2) -> bool {
        match self {
            Shape::Circle { radius } => p.x * p.x + p.y * p.y < radius * radius,
            Shape::Polygon { corners, reach } => {
                p.x.abs() <= *reach && p.y.abs() <= *reach && outline::contains(corners, p)
            }
        }
    }

    /// The farthest the shape reaches from the robot's centre, metres: no point farther
    /// away can lie inside.
    pub fn reach(&self) -> f64 {
        match self {
            Shape::Circle { radius } => *radius,
            Shape::Polygon { reach, .. } => *reach,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control::collision_monitor::config::ActionType;

    #[test]
    fn a_zone_without_points_or_radius_is_the_footprint() {
        let approach = PolygonConfig::new("approach", ActionType::Approach);
        let shape = Shape::of(&approach, 0.105);
        assert_eq!(shape, Shape::Circle { radius: 0.105 });
        assert!(shape.contains(Point2::new(0.1, 0.0)));
        assert!(!shape.contains(Point2::new(0.0, -0.11)));
        let stop = PolygonConfig::new("stop", ActionType::Stop).circle(0.15);
        assert!(Shape::of(&stop, 0.105).contains(Point2::new(-0.14, 0.0)));
    }

    #[test]
    fn a_polygon_reaches_as_far_as_its_farthest_corner() {
        let ahead = PolygonConfig::new("slowdown", ActionType::Slowdown).polygon(&[
            [0.3, 0.4],
            [0.3, -0.4],
            [0.0, -0.4],
            [0.0, 0.4],
        ]);
        let shape = Shape::of(&ahead, 0.105);
        assert!((shape.reach() - 0.5).abs() < 1e-12);
        assert!(shape.contains(Point2::new(0.2, 0.3)));
        assert!(!shape.contains(Point2::new(-0.1, 0.0)));
    }
}
