//! The collision monitor's zones round the robot, drawn while the monitor has control:
//! each enabled zone's outline (`!`, or braille dots), so a user sees what the robot is
//! keeping clear of, as RViz draws Nav2's collision monitor polygons.

use super::beliefs::set_dot;
use super::viewport::Viewport;
use crate::app::App;
use crate::control::collision_monitor::shape::Shape;
use crate::geometry::Point2;
use crate::pilot::behaviours::Behaviour;
use crate::tui::theme::Theme;
use ratatui::buffer::Buffer;

/// Draws the zones when the collision monitor's command is the one going out.
pub fn render(app: &App, vp: &Viewport, theme: Theme, buf: &mut Buffer) {
    let pilot = app.pilot();
    if pilot.arbiter().winner().map(|(b, _)| b) != Some(Behaviour::CollisionMonitor) {
        return;
    }
    let pose = pilot.estimated_pose();
    let braille = app.view().braille;
    let step = if braille { vp.scale / 2.0 } else { vp.scale } * 0.5;
    for zone in pilot.collision_zones().iter().filter(|z| z.config.enabled) {
        for p in outline(&zone.shape, step) {
            let at = pose.transform_point(p);
            if braille {
                set_dot(at, vp, theme.alert(), buf);
            } else if let Some(cell) = vp.cell(at) {
                let cell = &mut buf[cell];
                // Over free space and the robot's own marks, never over a wall.
                if cell.symbol() != "#" {
                    cell.set_char('!').set_style(theme.alert());
                }
            }
        }
    }
}

/// Points along `shape`'s edge (robot frame), at most `step` apart.
pub fn outline(shape: &Shape, step: f64) -> Vec<Point2> {
    let step = step.max(1e-3);
    match shape {
        Shape::Circle { radius } => {
            let n = ((std::f64::consts::TAU * radius / step) as usize).clamp(8, 720);
            (0..n)
                .map(|k| {
                    let a = std::f64::consts::TAU * k as f64 / n as f64;
                    Point2::new(radius * a.cos(), radius * a.sin())
                })
                .collect()
        }
        Shape::Polygon { corners, .. } => {
            let mut points = Vec::new();
            for (k, &a) in corners.iter().enumerate() {
                let b = corners[(k + 1) % corners.len()];
                let n = ((a.distance(b) / step) as usize).clamp(1, 400);
                points.extend((0..n).map(|i| {
                    let t = i as f64 / n as f64;
                    Point2::new(a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t)
                }));
            }
            points
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outlines_run_round_the_edge() {
        let circle = outline(&Shape::Circle { radius: 0.15 }, 0.01);
        assert!(circle.len() >= 90);
        assert!(circle.iter().all(|p| (p.x.hypot(p.y) - 0.15).abs() < 1e-9));
        let corners = vec![
            Point2::new(0.5, 0.15),
            Point2::new(0.5, -0.15),
            Point2::new(0.0, -0.15),
            Point2::new(0.0, 0.15),
        ];
        let square = outline(
            &Shape::Polygon {
                corners,
                reach: 0.52,
            },
            0.05,
        );
        assert!(square.contains(&Point2::new(0.5, 0.15)));
        assert!(
            square
                .iter()
                .all(|p| p.x.abs() <= 0.5 + 1e-9 && p.y.abs() <= 0.15 + 1e-9)
        );
    }
}
