//! The status panel: mode, link, pose, velocities, limits, loop rate, sim time.

use super::text::wrap_rows;
use crate::app::{App, LinkStatus};
use crate::geometry::Pose2;
use crate::pilot::mode::Mode;
use crate::tui::theme::Theme;
use ratatui::text::{Line, Span};

fn row(theme: Theme, label: &str, value: String) -> Line<'static> {
    Line::from(vec![
        Span::styled(format!("{label:<LABEL$}"), theme.label()),
        Span::styled(value, theme.value()),
    ])
}

fn pose_text(p: Pose2) -> String {
    // Rounded first, then + 0.0: a heading that rounds to zero shows no sign ("-0°").
    let (x, y) = (
        (p.x * 100.0).round() / 100.0 + 0.0,
        (p.y * 100.0).round() / 100.0 + 0.0,
    );
    let degrees = p.theta.to_degrees().round() + 0.0;
    format!("{x:6.2} {y:6.2} {degrees:4.0}°")
}

/// Session time as h:mm:ss.
fn clock_text(t: f64) -> String {
    let s = t.max(0.0).floor() as u64;
    format!("{}:{:02}:{:02}", s / 3600, (s / 60) % 60, s % 60)
}

/// A duration as m:ss.
fn minutes_text(t: f64) -> String {
    let s = t.max(0.0).floor() as u64;
    format!("{}:{:02}", s / 60, s % 60)
}

/// `text`, or a dash when there is nothing to list.
fn dash_if_empty<T>(items: &[T], text: String) -> String {
    if items.is_empty() { "-".into() } else { text }
}

/// Columns a row's label takes.
const LABEL: usize = 8;

/// `line` cut to `width` columns, its last column `…` when anything was cut.
fn fitted(line: Line<'static>, width: usize) -> Line<'static> {
    if line.width() <= width {
        return line;
    }
    let mut spans = Vec::new();
    let mut room = width;
    for span in line.spans {
        let n = span.content.chars().count();
        if n < room {
            room -= n;
            spans.push(span);
            continue;
        }
        let cut: String = span.content.chars().take(room.saturating_sub(1)).collect();
        spans.push(Span::styled(format!("{cut}…"), span.style));
        break;
    }
    Line::from(spans)
}

/// Status rows, most important first (a short panel shows the top ones), each fitted to
/// `width` columns.
pub fn lines(app: &App, theme: Theme, width: usize) -> Vec<Line<'static>> {
    rows(app, theme, width)
        .into_iter()
        .map(|l| fitted(l, width))
        .collect()
}

fn rows(app: &App, theme: Theme, width: usize) -> Vec<Line<'static>> {
    let link = match app.pilot().link_status() {
        LinkStatus::Ok => "ok".to_string(),
        LinkStatus::Lost(_) => "LOST".to_string(),
        LinkStatus::Back => "back, press a key".to_string(),
    };
    let (cmd, meas) = (app.pilot().commanded(), app.pilot().measured());
    let t = app.pilot().teleop();
    let (max_v, max_w) = t.limits();
    let mut rows = vec![row(theme, "Mode", app.pilot().mode().label().to_string())];
    rows.extend(navigation_rows(app, theme, width.saturating_sub(LABEL)));
    rows.push(row(theme, "Link", format!("{} {link}", app.link().label())));
    if let LinkStatus::Lost(reason) = app.pilot().link_status() {
        // Why, as the link says it now (its waiting time counts up), over up to three
        // rows; the Link row already says it is lost.
        let reason = reason.strip_prefix("link lost: ").unwrap_or(reason);
        let parts = wrap_rows(reason, width.saturating_sub(LABEL), 3);
        rows.extend(parts.into_iter().map(|p| row(theme, "", p)));
    }
    for (label, value) in app.link().details(app.now()) {
        rows.push(row(theme, label, value));
    }
    rows.push(row(theme, "Pose", pose_text(app.pilot().estimated_pose())));
    let (sx, sy, st) = app.pilot().pose_sigma();
    rows.push(row(
        theme,
        "Sigma",
        format!("{sx:6.3} {sy:6.3} {:4.1}°", st.to_degrees()),
    ));
    if let Some(mcl) = app.pilot().mcl() {
        let st = mcl.status();
        rows.push(row(
            theme,
            "MCL",
            format!("{} particles, ESS {:.0}", st.particles, st.effective),
        ));
        let state = if st.converged {
            "converged".to_string()
        } else if st.clusters > 1 {
            format!(
                "{} hypotheses, best {:.0} %",
                st.clusters,
                100.0 * st.cluster_weight
            )
        } else {
            format!("searching, spread {:.2} m", mcl.position_std())
        };
        rows.push(row(theme, "Locate", state));
    }
    if let Some(truth) = app.true_pose().filter(|_| app.view().show_truth) {
        rows.push(row(theme, "Truth", pose_text(truth)));
        let est = app.pilot().estimated_pose();
        let dtheta = crate::geometry::wrap_angle(truth.theta - est.theta);
        rows.push(row(
            theme,
            "Error",
            format!(
                "{:.3} m {:4.1}°",
                (truth.x - est.x).hypot(truth.y - est.y),
                // An error that rounds to zero shows no sign.
                (dtheta.to_degrees() * 10.0).round() / 10.0 + 0.0
            ),
        ));
    }
    rows.extend([
        row(
            theme,
            "Cmd",
            format!("v {:5.2} w {:5.2}", cmd.linear, cmd.angular),
        ),
        row(
            theme,
            "Meas",
            format!("v {:5.2} w {:5.2}", meas.linear, meas.angular),
        ),
        row(
            theme,
            "Speed",
            format!(
                "v {:.2}/{max_v:.2} w {:.1}/{max_w:.1}",
                t.linear_speed, t.angular_speed
            ),
        ),
        row(
            theme,
            "SLAM",
            if app.pilot().mode() == crate::app::mode::Mode::Race {
                format!(
                    "{} lm, every {} frames",
                    app.pilot().slam().landmark_count(),
                    app.config().race.correct_every
                )
            } else {
                format!(
                    "{} lm, {} rejected",
                    app.pilot().slam().landmark_count(),
                    app.pilot().slam().rejected()
                )
            },
        ),
        row(
            theme,
            "Gripper",
            app.pilot()
                .gripper()
                .map_or("-".into(), |g| g.label().to_string()),
        ),
        row(
            theme,
            "Loop",
            format!("{:.0} Hz  t {}", app.loop_rate(), clock_text(app.now())),
        ),
    ]);
    if let Some(twin) = app.link().ground_truth() {
        rows.push(row(
            theme,
            "Hits",
            format!("{} collisions", twin.collisions()),
        ));
    }
    // In words, as the help says them: "forward + turn left".
    let held: Vec<String> = app
        .held_keys()
        .iter()
        .map(|a| a.name().replace('_', " "))
        .collect();
    rows.push(row(
        theme,
        "Driving",
        dash_if_empty(&held, held.join(" + ")),
    ));
    let seen: Vec<String> = app.in_view().iter().map(|id| id.to_string()).collect();
    rows.push(row(
        theme,
        "Seen",
        dash_if_empty(&seen, format!("{}: {}", seen.len(), seen.join(" "))),
    ));
    rows
}

/// The path and its progress, right under the mode: what an autonomous mode is doing.
fn navigation_rows(app: &App, theme: Theme, room: usize) -> Vec<Line<'static>> {
    let mut rows = Vec::new();
    if let Some(m) = app.pilot().mission() {
        // Out of exploration the mission is paused, not running: `e` takes it up again.
        let paused = app.pilot().mode() != Mode::Exploration;
        let state = if paused {
            "paused: e resumes".to_string()
        } else {
            m.state_label()
        };
        // The state and its target, and why, can be long: two rows each, broken
        // between words.
        let reason = if paused { String::new() } else { m.reason() };
        for (label, text) in [("Mission", state), ("Why", reason)] {
            for (k, part) in wrap_rows(&text, room, 2).into_iter().enumerate() {
                rows.push(row(theme, if k == 0 { label } else { "" }, part));
            }
        }
        let total = match app.config().mission.total_blocks {
            0 => "?".to_string(),
            n => n.to_string(),
        };
        rows.push(row(
            theme,
            "Blocks",
            format!(
                "{}/{total} done {} seen {}",
                m.delivered(),
                m.known_blocks(),
                minutes_text(app.pilot().mission_elapsed())
            ),
        ));
    }
    let controller = app.pilot().follower().controller().label();
    if let Some(f) = app.pilot().following() {
        rows.push(row(
            theme,
            "Path",
            format!("{:.2} m, {:.0} s left", f.remaining, f.eta),
        ));
        rows.push(row(
            theme,
            "XTE",
            format!("{:+.1} cm  {controller}", f.cross_track * 100.0),
        ));
    } else if let Some(route) = app.pilot().route() {
        let state = if app.pilot().arrived() {
            "arrived at"
        } else {
            "to"
        };
        rows.push(row(
            theme,
            "Path",
            format!("{:.2} m {state} {}", route.plan.length, route.label),
        ));
    }
    if let Some(progress) = app.pilot().waypoints().progress() {
        rows.push(row(theme, "Route", progress));
    }
    if let Some(c) = app.goal_cursor() {
        rows.push(row(
            theme,
            "Cursor",
            format!("{:6.2} {:6.2}  {controller}", c.x, c.y),
        ));
    }
    rows
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn minutes_read_minutes_and_seconds() {
        assert_eq!(minutes_text(125.5), "2:05");
    }

    #[test]
    fn clock_reads_hours_minutes_seconds() {
        assert_eq!(clock_text(3725.9), "1:02:05");
    }

    #[test]
    fn a_row_too_long_ends_in_an_ellipsis_and_one_that_fits_is_kept() {
        let theme = Theme::from_env(None);
        let long = row(theme, "Path", "1.72 m arrived at (1.62, -0.53)".into());
        let cut = fitted(long, 30);
        let text: String = cut.spans.iter().map(|s| s.content.as_ref()).collect();
        assert_eq!(text, "Path    1.72 m arrived at (1.…");
        assert_eq!(cut.width(), 30);
        let short = fitted(row(theme, "Mode", "MANUAL".into()), 30);
        assert_eq!(short.width(), 14);
    }

    #[test]
    fn a_heading_that_rounds_to_zero_has_no_sign() {
        let text = pose_text(Pose2::new(-0.001, 0.5, -0.004));
        assert!(!text.contains('-'), "{text}");
    }
}
