//! The replay's view "as recorded": the map, estimate, landmarks, plan, status and log
//! exactly as the recording holds them at the playback's time, whatever today's code
//! would make of the data.

use crate::app::App;
use crate::app::log::format_time;
use crate::geometry::Point2;
use crate::perception::markers::MarkerCategory;
use crate::record::recorded::Recorded;
use crate::tui::theme::{Theme, marker_glyph};
use crate::tui::widgets::beliefs::draw_ellipse;
use crate::tui::widgets::map::{Viewport, draw_occupancy_ascii, draw_robot};
use crate::tui::widgets::path::{draw_polyline, put};
use crate::tui::widgets::text::fit;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Modifier;
use ratatui::text::{Line, Span};

/// The map at session time `t`: the newest recorded grid, plan, landmarks and estimate,
/// and the twin's true pose (`o`) when the view shows the truth.
pub fn map(app: &App, recorded: &Recorded, t: f64, theme: Theme, area: Rect, buf: &mut Buffer) {
    let scale = app.view().scale(app.fitted_scale());
    let vp = Viewport::new(area, app.map_center(), scale);
    if let Some(grid) = Recorded::at(&recorded.maps, t) {
        draw_occupancy_ascii(grid, &vp, theme, buf);
    }
    if let Some(points) = Recorded::at(&recorded.plans, t).filter(|p| !p.is_empty()) {
        draw_polyline(points, &vp, theme.path(), buf);
        if let Some(goal) = points.last() {
            put(buf, &vp, *goal, 'G', theme.path());
        }
    }
    if let Some(list) = Recorded::at(&recorded.landmarks, t) {
        for l in list {
            let category = MarkerCategory::of(l.id);
            draw_ellipse(
                l.mean,
                &l.covariance,
                &vp,
                false,
                theme.marker(category),
                buf,
            );
        }
        for l in list {
            if let Some(cell) = vp.cell(l.mean) {
                let category = MarkerCategory::of(l.id);
                buf[cell]
                    .set_char(marker_glyph(category))
                    .set_style(theme.marker(category).add_modifier(Modifier::BOLD));
            }
        }
    }
    if app.view().show_truth
        && let Some(truth) = recorded.truth_at(t)
    {
        draw_robot(truth.pose(), 'o', &vp, theme.truth(), buf);
    }
    if let Some(e) = recorded.estimate_at(t) {
        let cov = e.covariance.fixed_view::<2, 2>(0, 0).into_owned();
        draw_ellipse(e.pose.position(), &cov, &vp, false, theme.robot(), buf);
        draw_robot(e.pose, '@', &vp, theme.robot(), buf);
    }
}

fn row(label: &str, value: String, theme: Theme, width: usize) -> Line<'static> {
    let label = format!("{label:<9}");
    let room = width.saturating_sub(label.chars().count());
    Line::from(vec![
        Span::styled(label, theme.label()),
        Span::styled(fit(&value, room), theme.value()),
    ])
}

/// The status panel at `t`: mode, estimate and its spread, landmarks, the command sent,
/// and the error against the twin's truth.
pub fn status(recorded: &Recorded, t: f64, theme: Theme, width: usize) -> Vec<Line<'static>> {
    let mut out = vec![row("time", format_time(t), theme, width)];
    let mode = Recorded::at(&recorded.modes, t)
        .cloned()
        .unwrap_or_default();
    out.push(row("mode", mode, theme, width));
    if let Some(e) = recorded.estimate_at(t) {
        let p = e.pose;
        out.push(row(
            "pose",
            format!("{:.2} {:.2} {:.0}°", p.x, p.y, p.theta.to_degrees()),
            theme,
            width,
        ));
        let sigma = (e.covariance[(0, 0)] + e.covariance[(1, 1)])
            .max(0.0)
            .sqrt();
        out.push(row(
            "σ pos",
            format!("{:.1} cm", sigma * 100.0),
            theme,
            width,
        ));
        if let Some(truth) = recorded.truth_at(t) {
            let gap = p.position().distance(Point2::new(truth.x, truth.y));
            out.push(row("error", format!("{:.1} cm", gap * 100.0), theme, width));
        }
    }
    let landmarks = Recorded::at(&recorded.landmarks, t).map_or(0, Vec::len);
    out.push(row("landmks", landmarks.to_string(), theme, width));
    if let Some(&(_, v, w)) = Recorded::newest(&recorded.commands, t, |c| c.0) {
        out.push(row(
            "cmd_vel",
            format!("{v:.2} m/s {w:.2} rad/s"),
            theme,
            width,
        ));
    }
    out
}

/// The newest `rows` log lines recorded up to `t`, cut to `width`.
pub fn log(
    recorded: &Recorded,
    t: f64,
    theme: Theme,
    rows: usize,
    width: usize,
) -> Vec<Line<'static>> {
    let n = Recorded::upto(&recorded.logs, t, |l| l.time);
    recorded.logs[..n]
        .iter()
        .skip(n.saturating_sub(rows))
        .map(|l| {
            let stamp = format!("{} ", format_time(l.time));
            let room = width.saturating_sub(stamp.chars().count());
            let text = crate::app::log::sourced(l.source.as_deref(), &l.text);
            Line::from(vec![
                Span::styled(stamp, theme.label()),
                Span::styled(fit(&text, room), theme.level(l.level)),
            ])
        })
        .collect()
}
