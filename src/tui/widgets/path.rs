//! The planned path, its goal, the route's numbered waypoints, and thinking mode's goal
//! cursor with RViz's arrow from a pose's anchor, over the map.

use super::viewport::Viewport;
use crate::app::App;
use crate::geometry::Point2;
use crate::tui::theme::Theme;
use ratatui::buffer::Buffer;
use ratatui::style::{Modifier, Style};

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
    waypoints(app, vp, theme, buf);
}

/// The route's waypoints numbered 1 2 3 … as Nav2's panel numbers its markers; the one
/// being driven to reversed.
fn waypoints(app: &App, vp: &Viewport, theme: Theme, buf: &mut Buffer) {
    let route = app.pilot().waypoints();
    let current = route.current();
    for (i, w) in route.goals().iter().enumerate() {
        let Some((x, y)) = vp.cell(w.position) else {
            continue;
        };
        let mut style = theme.path().add_modifier(Modifier::BOLD);
        if current == Some(i) {
            style = style.add_modifier(Modifier::REVERSED);
        }
        let right = vp.area.x + vp.area.width;
        for (k, digit) in (i + 1).to_string().chars().enumerate() {
            let column = x.saturating_add(k as u16);
            if column < right {
                buf[(column, y)].set_char(digit).set_style(style);
            }
        }
    }
}

/// Thinking mode's cursor, drawn over everything else on the map (the robot and the
/// twin's truth included); while a pose waits for its heading, RViz's arrow from the
/// anchor to the cursor, its head at the cursor.
pub fn cursor(app: &App, vp: &Viewport, theme: Theme, buf: &mut Buffer) {
    let Some(cursor) = app.goal_cursor() else {
        return;
    };
    let Some(anchor) = app.pose_anchor() else {
        put(buf, vp, cursor, 'X', theme.cursor());
        return;
    };
    let (dx, dy) = (cursor.x - anchor.x, cursor.y - anchor.y);
    if dx.hypot(dy) < 1e-9 {
        put(buf, vp, anchor, 'X', theme.cursor());
        return;
    }
    let (shaft, head) = arrow_glyphs(dy.atan2(dx));
    let step = vp.scale / DOTS_PER_COLUMN;
    let n = (dx.hypot(dy) / step).ceil().max(1.0) as usize;
    let head_cell = vp.cell(cursor);
    for k in 0..n {
        let t = k as f64 / n as f64;
        let p = Point2::new(anchor.x + t * dx, anchor.y + t * dy);
        if vp.cell(p) != head_cell {
            put(buf, vp, p, shaft, theme.cursor());
        }
    }
    put(buf, vp, anchor, '+', theme.cursor());
    put(buf, vp, cursor, head, theme.cursor());
}

/// The shaft and head of an arrow pointing at `angle` (radians, map frame), in screen
/// cells, which are twice as tall as they are wide.
fn arrow_glyphs(angle: f64) -> (char, char) {
    let screen = (angle.sin() / 2.0).atan2(angle.cos());
    let octant = ((screen / std::f64::consts::FRAC_PI_4).round() as i32).rem_euclid(8);
    match octant {
        0 => ('-', '→'),
        1 => ('/', '↗'),
        2 => ('|', '↑'),
        3 => ('\\', '↖'),
        4 => ('-', '←'),
        5 => ('/', '↙'),
        6 => ('|', '↓'),
        _ => ('\\', '↘'),
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
