//! Keepout and speed zones on the map: every screen cell of a keepout zone `░`, the
//! outline of a speed zone `=` (under walls), and while a zone is being drawn its first
//! corner `+`.

use super::viewport::Viewport;
use crate::app::App;
use crate::geometry::Point2;
use crate::map::zones::{Rect, ZoneKind};
use crate::tui::theme::Theme;
use ratatui::buffer::Buffer;
use ratatui::style::Style;

pub const KEEPOUT_GLYPH: char = '░';
pub const SPEED_GLYPH: char = '=';
pub const CORNER_GLYPH: char = '+';

/// Draws the zones and the corner of the one being drawn.
pub fn render(app: &App, vp: &Viewport, theme: Theme, buf: &mut Buffer) {
    for zone in app.pilot().zones().zones() {
        match zone.kind {
            ZoneKind::Keepout => cells(&zone.rect, vp, true, KEEPOUT_GLYPH, theme.alert(), buf),
            ZoneKind::Speed(_) => cells(&zone.rect, vp, false, SPEED_GLYPH, theme.path(), buf),
        }
    }
    if let Some((corner, _)) = app.zone_drawing().anchor()
        && let Some(cell) = vp.cell(corner)
    {
        buf[cell].set_char(CORNER_GLYPH).set_style(theme.cursor());
    }
}

/// The screen cells of `rect` (all, or its edge only), drawn with `glyph`.
fn cells(rect: &Rect, vp: &Viewport, fill: bool, glyph: char, style: Style, buf: &mut Buffer) {
    let (w, h) = (f64::from(vp.area.width), f64::from(vp.area.height));
    // Columns and rows the rectangle spans, clamped to the screen.
    let col = |x: f64| ((x - vp.left) / vp.scale).floor().clamp(-1.0, w);
    let row = |y: f64| ((vp.top - y) / (2.0 * vp.scale)).floor().clamp(-1.0, h);
    let (c0, c1) = (col(rect.x0), col(rect.x1));
    let (r0, r1) = (row(rect.y1), row(rect.y0));
    let mut r = r0;
    while r <= r1 {
        let mut c = c0;
        while c <= c1 {
            let edge = r == r0 || r == r1 || c == c0 || c == c1;
            let on_screen = c >= 0.0 && r >= 0.0 && c < w && r < h;
            if on_screen && (fill || edge) {
                let at = Point2::new(
                    vp.left + (c + 0.5) * vp.scale,
                    vp.top - (r + 0.5) * 2.0 * vp.scale,
                );
                // A keepout zone is lethal on the planning map (`#`): its fill shows it is
                // a zone; a speed zone's edge stays under walls.
                if let Some(cell) = vp.cell(at)
                    && (fill || buf[cell].symbol() != "#")
                {
                    buf[cell].set_char(glyph).set_style(style);
                }
            }
            c += 1.0;
        }
        r += 1.0;
    }
}
