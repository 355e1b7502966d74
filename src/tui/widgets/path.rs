//! The planned path, its goal and thinking mode's goal cursor, over the map.

use super::viewport::Viewport;
use crate::app::App;
use crate::geometry::Point2;
use crate::tui::theme::Theme;
use ratatui::buffer::Buffer;
use ratatui::style::Style;

/// Path dots every this fraction of a screen column, so no cell on the way is skipped.
const DOTS_PER_COLUMN: f64 = 2.0;

pub fn render(app: &App, vp: &Viewport, theme: Theme, buf: &mut Buffer) {
    // Racing is driving by hand: a path planned before is not what the robot follows.
    let racing = app.pilot().mode() == crate::pilot::mode::Mode::Race;
    if let Some(route) = app.pilot().route().filter(|_| !racing) {
        let points: Vec<Point2> = route
            .plan
            .trajectory
            .points
            .iter()
            .map(|p| p.position)
            .collect();
        draw_polyline(&points, vp, theme.path(), buf);
        put(buf, vp, route.goal, 'G', theme.path());
    }
    if let Some(cursor) = app.goal_cursor() {
        put(buf, vp, cursor, 'X', theme.cursor());
    }
}

pub fn draw_polyline(points: &[Point2], vp: &Viewport, style: Style, buf: &mut Buffer) {
    let step = vp.scale / DOTS_PER_COLUMN;
    for pair in points.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        let n = (a.distance(b) / step).ceil().max(1.0) as usize;
        for k in 0..=n {
            let t = k as f64 / n as f64;
            let p = Point2::new(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
            put(buf, vp, p, '•', style);
        }
    }
}

pub fn put(buf: &mut Buffer, vp: &Viewport, p: Point2, glyph: char, style: Style) {
    if let Some(cell) = vp.cell(p) {
        buf[cell].set_char(glyph).set_style(style);
    }
}
