//! Lidar SLAM's pose graph over the map (`G`), as RViz shows slam_toolbox's graph: each
//! keyframe a node (`○`), each edge a line between its nodes, the sequential chain drawn
//! with line glyphs (`- / | \`) and loop closures as `~` in another colour.

use super::beliefs::set_dot;
use super::viewport::Viewport;
use crate::app::App;
use crate::geometry::Point2;
use crate::slam::lidar::EdgeKind;
use crate::tui::theme::Theme;
use ratatui::buffer::Buffer;
use ratatui::style::Style;

/// The graph, when the view shows it and lidar SLAM runs.
pub fn render(app: &App, vp: &Viewport, theme: Theme, buf: &mut Buffer) {
    let Some(sp) = app.pilot().lidar_slam().filter(|_| app.view().graph) else {
        return;
    };
    let braille = app.view().braille;
    let graph = sp.slam.graph();
    // Loops last, so that they stay visible where they cross the chain.
    let mut edges: Vec<_> = graph.edges.iter().collect();
    edges.sort_by_key(|e| e.kind == EdgeKind::Loop);
    for edge in edges {
        let (Some(a), Some(b)) = (graph.poses.get(edge.from), graph.poses.get(edge.to)) else {
            continue;
        };
        let (a, b) = (a.position(), b.position());
        let (glyph, style) = match edge.kind {
            EdgeKind::Loop => ('~', theme.loop_edge()),
            EdgeKind::Sequential => (line_glyph(a, b), theme.graph()),
        };
        // Points half a dot apart along the edge, so that it has no gaps.
        let step = if braille {
            vp.scale / 4.0
        } else {
            vp.scale / 2.0
        };
        let n = ((a.distance(b) / step).ceil() as usize).clamp(1, 4000);
        for k in 0..=n {
            let f = k as f64 / n as f64;
            let p = Point2::new(a.x + f * (b.x - a.x), a.y + f * (b.y - a.y));
            mark(p, glyph, vp, braille, style, buf);
        }
    }
    for pose in &graph.poses {
        mark(pose.position(), '○', vp, braille, theme.graph(), buf);
    }
}

/// The line glyph nearest an edge's direction on screen, where a row is twice a column's
/// height.
fn line_glyph(a: Point2, b: Point2) -> char {
    let (dx, dy) = (b.x - a.x, (b.y - a.y) / 2.0);
    let angle = dy.atan2(dx).to_degrees().rem_euclid(180.0);
    match angle {
        a if !(22.5..157.5).contains(&a) => '-',
        a if a < 67.5 => '/',
        a if a < 112.5 => '|',
        _ => '\\',
    }
}

/// `glyph` at `p` over free, unknown or passed-over space (walls, markers and the robot
/// keep theirs), or a braille dot there.
fn mark(p: Point2, glyph: char, vp: &Viewport, braille: bool, style: Style, buf: &mut Buffer) {
    if braille {
        set_dot(p, vp, style, buf);
    } else if let Some(cell) = vp.cell(p) {
        let cell = &mut buf[cell];
        if matches!(
            cell.symbol(),
            " " | "." | ":" | "·" | "'" | "-" | "/" | "|" | "\\" | "~"
        ) {
            cell.set_char(glyph).set_style(style);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edges_take_the_glyph_of_their_direction_on_screen() {
        let o = Point2::new(0.0, 0.0);
        assert_eq!(line_glyph(o, Point2::new(1.0, 0.1)), '-');
        assert_eq!(line_glyph(o, Point2::new(-1.0, 0.0)), '-');
        assert_eq!(line_glyph(o, Point2::new(0.0, 1.0)), '|');
        // A row is twice a column's height: 45° in the world is flatter on screen.
        assert_eq!(line_glyph(o, Point2::new(1.0, 2.0)), '/');
        assert_eq!(line_glyph(o, Point2::new(1.0, -2.0)), '\\');
    }
}
