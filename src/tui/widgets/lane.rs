//! The lane panel (lane mode, seed 000 §2-§3): the lane camera's newest frame in colour
//! half blocks with the fitted lines' bird's-eye view beside its text, the lateral error
//! and curvature, the traffic light's colour and the barrier's state and angle, and what
//! holds the robot.

use crate::app::App;
use crate::data::{ColourThumbnail, LaneSighting};
use crate::tui::theme::Theme;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::text::Line;

/// The panel's text rows.
pub fn lines(app: &App, theme: Theme) -> Vec<Line<'static>> {
    let lane = app.pilot().lane();
    let Some(s) = lane.last() else {
        return vec![
            Line::styled("no lane frames yet", theme.label()),
            Line::styled("(a world with a [track]; vision build)", theme.label()),
        ];
    };
    let mut out = Vec::new();
    if let Some(e) = &s.error {
        out.push(Line::styled(format!("frame refused: {e}"), theme.alert()));
    }
    out.push(Line::styled(lane_text(s), theme.value()));
    let light = match s.light {
        Some(l) => format!("light {} {:.2} m", l.colour.label(), l.range),
        None => "light -".into(),
    };
    let barrier = match s.barrier {
        Some(b) => format!(
            "barrier {} {:.0}° {:.2} m",
            b.state.label(),
            b.angle_deg,
            b.range
        ),
        None => "barrier -".into(),
    };
    out.push(Line::styled(light, theme.value()));
    out.push(Line::styled(barrier, theme.value()));
    let wait = lane.wait().map_or("driving".into(), |w| w.text());
    out.push(Line::styled(wait, theme.label()));
    out
}

/// "lateral +12 mm  κ 0.84/m" (positive: the lane centre is to the right).
fn lane_text(s: &LaneSighting) -> String {
    match (s.error_px, s.curvature) {
        (Some(e), k) => {
            let mm = e * LaneSighting::MM_PER_PX;
            let k = k.map_or("-".into(), |k| format!("{k:+.2}/m"));
            format!("lateral {mm:+.0} mm  κ {k}")
        }
        (None, _) => "no lane line in view".into(),
    }
}

/// Draws the thumbnail into `area` in colour half blocks (two pixels a cell), scaled to
/// fill it; grey shades on a terminal without colour.
pub fn thumbnail(thumb: &ColourThumbnail, theme: Theme, area: Rect, buf: &mut Buffer) {
    if thumb.width == 0 || thumb.height == 0 {
        return;
    }
    let (cols, rows) = (usize::from(area.width), usize::from(area.height));
    let sample = |x: usize, y: usize| {
        thumb.at(
            x * thumb.width / cols.max(1),
            y * thumb.height / (2 * rows).max(1),
        )
    };
    for row in 0..rows {
        for col in 0..cols {
            let cell = &mut buf[(area.x + col as u16, area.y + row as u16)];
            let (top, bottom) = (sample(col, row * 2), sample(col, row * 2 + 1));
            if theme.color {
                cell.set_char('▀');
                let rgb = |p: [u8; 3]| Color::Rgb(p[0], p[1], p[2]);
                cell.set_style(Style::new().fg(rgb(top)).bg(rgb(bottom)));
            } else {
                const SHADES: [char; 5] = [' ', '░', '▒', '▓', '█'];
                // ITU-R BT.601 luma of the two pixels' mean.
                let luma = |p: [u8; 3]| {
                    (299 * u32::from(p[0]) + 587 * u32::from(p[1]) + 114 * u32::from(p[2])) / 1000
                };
                let level = (luma(top) + luma(bottom)) / 2;
                cell.set_char(SHADES[level as usize * 5 / 256]);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_error_reads_in_millimetres_with_its_side() {
        let s = LaneSighting {
            error_px: Some(-23.4),
            curvature: Some(0.5),
            ..LaneSighting::default()
        };
        assert_eq!(lane_text(&s), "lateral -23 mm  κ +0.50/m");
        assert_eq!(lane_text(&LaneSighting::default()), "no lane line in view");
    }
}
