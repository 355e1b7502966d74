//! The status panel: mode, link, pose, velocities, limits, loop rate, sim time.

use super::rows::{Need, Row, fit_rows};
use crate::app::{App, LinkStatus};
use crate::geometry::Pose2;
use crate::pilot::mode::Mode;
use crate::tui::theme::Theme;
use ratatui::text::Line;

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

/// Which behaviour has control (its command goes out), and why when a safety behaviour
/// overrides the task.
fn behaviour_row(app: &App) -> Row {
    let text = match app.pilot().arbiter().winner() {
        Some((b, why)) if b.is_safety() && !why.is_empty() => format!("{b}: {why}"),
        Some((b, _)) => b.to_string(),
        None => "idle".to_string(),
    };
    Row::new("Control", text, Need::Some).wrapping(2)
}

/// The sensors lost now, each with how long and what it changes, and the faults injected
/// into the twin now; no row while every sensor answers and no fault is in force.
fn health_row(app: &App) -> Option<Row> {
    let health = app.pilot().sensor_health();
    let mut parts: Vec<String> = (health.lost().into_iter())
        .map(|s| {
            let since = health.lost_since(s).unwrap_or(app.now());
            format!("{s} LOST {:.0} s", (app.now() - since).max(0.0))
        })
        .collect();
    if let Some(faults) = app.faults() {
        let kinds = faults.active_kinds();
        if !kinds.is_empty() {
            let names: Vec<String> = kinds.iter().map(|k| k.to_string()).collect();
            parts.push(format!("fault {}", names.join(", ")));
        }
    }
    (!parts.is_empty()).then(|| Row::new("Sensors", parts.join("; "), Need::Must).wrapping(2))
}

/// Status rows, fitted to `width` x `height`: long values wrap, and a short panel keeps
/// the rows a user needs most (mode, link, pose, mission).
pub fn lines(app: &App, theme: Theme, width: usize, height: usize) -> Vec<Line<'static>> {
    fit_rows(rows(app), theme, width, height)
}

fn rows(app: &App) -> Vec<Row> {
    let waiting = !app.pilot().link_ever_up();
    let link = match app.pilot().link_status() {
        LinkStatus::Ok => "ok".to_string(),
        // Nothing was ever linked: the robot is awaited, not lost.
        LinkStatus::Lost(_) if waiting => "waiting for robot".to_string(),
        LinkStatus::Lost(_) => "LOST".to_string(),
        LinkStatus::Back => "back, press a key".to_string(),
    };
    let (cmd, meas) = (app.pilot().commanded(), app.pilot().measured());
    let t = app.pilot().teleop();
    let (max_v, max_w) = t.limits();
    let mut rows = Vec::new();
    // A notable event (a loop closed) stands first, highlighted, for a few seconds: seen
    // however small the log pane is.
    if let Some(flashed) = app.log_book().flashing(app.now()) {
        rows.push(
            Row::new("Event", flashed.sourced_text(), Need::Must)
                .wrapping(3)
                .flashing(),
        );
    }
    rows.push(Row::new("Mode", app.pilot().mode().label(), Need::Must));
    rows.push(behaviour_row(app));
    rows.extend(health_row(app));
    if let Some(limit) = app.pilot().zone_speed_limit() {
        rows.push(Row::new(
            "Zone",
            format!("speed limit {limit:.2} m/s"),
            Need::High,
        ));
    }
    rows.extend(navigation_rows(app));
    rows.extend(super::tag_route::status_rows(app));
    rows.push(Row::new("Link", format!("{} {link}", app.link().label()), Need::Must).wrapping(2));
    if let LinkStatus::Lost(reason) = app.pilot().link_status() {
        // Why, as the link says it now (its waiting time counts up), over up to three
        // rows; the Link row already says it is lost or awaited.
        let reason = reason.strip_prefix("link lost: ").unwrap_or(reason);
        rows.push(Row::new("", reason, Need::Must).wrapping(3));
    }
    for (label, value) in app.link().details(app.now()) {
        rows.push(Row::new(label, value, Need::Some).wrapping(3));
    }
    // Until MCL has found the robot, its mean may lie anywhere (inside a pillar): the
    // pose is not known, and the row says so.
    let lost = app.pilot().mcl().is_some_and(|m| !m.status().converged);
    let pose = if lost {
        "unknown: not localised yet".to_string()
    } else {
        pose_text(app.pilot().estimated_pose())
    };
    rows.push(Row::new("Pose", pose, Need::Must).wrapping(2));
    let (sx, sy, st) = app.pilot().pose_sigma();
    rows.push(Row::new(
        "Sigma",
        format!("{sx:6.3} {sy:6.3} {:4.1}°", st.to_degrees()),
        Need::Low,
    ));
    if let Some(mcl) = app.pilot().mcl() {
        let st = mcl.status();
        let c = &mcl.config().particles;
        rows.push(
            Row::new(
                "MCL",
                format!(
                    "{} particles (KLD {}-{}), ESS {:.0}",
                    st.particles, c.min_particles, c.max_particles, st.effective
                ),
                Need::Some,
            )
            .wrapping(2),
        );
        // "localised", "localising: 3 hypotheses", "lost: ...": the filter's own word.
        let state = st.summary();
        rows.push(Row::new("Locate", state, Need::High).wrapping(2));
    }
    rows.extend(lidar_slam_rows(app));
    if let Some(truth) = app.true_pose().filter(|_| app.view().show_truth) {
        rows.push(Row::new("Truth", pose_text(truth), Need::Low));
        let est = app.pilot().estimated_pose();
        let dtheta = crate::geometry::wrap_angle(truth.theta - est.theta);
        rows.push(Row::new(
            "Error",
            format!(
                "{:.3} m {:4.1}°",
                (truth.x - est.x).hypot(truth.y - est.y),
                // An error that rounds to zero shows no sign.
                (dtheta.to_degrees() * 10.0).round() / 10.0 + 0.0
            ),
            Need::Some,
        ));
    }
    rows.extend([
        Row::new(
            "Cmd",
            format!("v {:5.2} w {:5.2}", cmd.linear, cmd.angular),
            Need::Some,
        ),
        Row::new(
            "Meas",
            format!("v {:5.2} w {:5.2}", meas.linear, meas.angular),
            Need::Low,
        ),
        Row::new(
            "Speed",
            format!(
                "v {:.2}/{max_v:.2} w {:.1}/{max_w:.1}",
                t.linear_speed, t.angular_speed
            ),
            Need::High,
        ),
    ]);
    // Under MCL the pose comes from the known map, not from SLAM's landmarks.
    if app.pilot().mcl().is_none() {
        rows.push(Row::new("SLAM", slam_text(app), Need::Low));
    }
    rows.extend([
        Row::new(
            "Gripper",
            app.pilot().gripper().map_or("-", |g| g.label()),
            Need::High,
        ),
        Row::new(
            "Loop",
            format!("{:.0} Hz  t {}", app.loop_rate(), clock_text(app.now())),
            Need::Low,
        ),
    ]);
    if let Some(twin) = app.link().ground_truth() {
        rows.push(Row::new(
            "Hits",
            format!("{} collisions", twin.collisions()),
            Need::High,
        ));
    }
    // In words, as the help says them: "forward + turn left".
    let held: Vec<String> = app
        .held_keys()
        .iter()
        .map(|a| a.name().replace('_', " "))
        .collect();
    rows.push(
        Row::new(
            "Driving",
            dash_if_empty(&held, held.join(" + ")),
            Need::Some,
        )
        .wrapping(2),
    );
    let seen: Vec<String> = app.in_view().iter().map(|id| id.to_string()).collect();
    rows.push(
        Row::new(
            "Seen",
            dash_if_empty(&seen, format!("{}: {}", seen.len(), seen.join(" "))),
            Need::Some,
        )
        .wrapping(3),
    );
    rows
}

/// Lidar SLAM's graph and how well the last scan matched, when it runs.
fn lidar_slam_rows(app: &App) -> Vec<Row> {
    let Some(sp) = app.pilot().lidar_slam() else {
        return Vec::new();
    };
    let keyframes = sp.slam.graph().poses.len();
    let loops = sp.slam.loops();
    let plural = |n: usize, one: &str| format!("{n} {one}{}", if n == 1 { "" } else { "s" });
    vec![
        Row::new(
            "Graph",
            format!(
                "{}, {}",
                plural(keyframes, "keyframe"),
                plural(loops, "loop")
            ),
            Need::Some,
        )
        .wrapping(2),
        Row::new(
            "Match",
            format!("response {:.2}", sp.slam.last_response()),
            Need::Low,
        ),
    ]
}

/// SLAM's landmarks and how often it corrects (racing) or what it rejected.
fn slam_text(app: &App) -> String {
    let count = app.pilot().slam().landmark_count();
    if app.pilot().mode() == Mode::Race {
        format!(
            "{count} lm, every {} frames",
            app.config().race.correct_every
        )
    } else {
        format!("{count} lm, {} rejected", app.pilot().slam().rejected())
    }
}

/// The mission's blocks in words: delivered (of how many, when the world says), found
/// so far, and how long the mission has run.
fn blocks_text(app: &App, delivered: usize, found: usize) -> String {
    let of = match app.config().mission.total_blocks {
        0 => String::new(),
        n => format!(" of {n}"),
    };
    format!(
        "{delivered}{of} delivered, {found} found (mission {})",
        minutes_text(app.pilot().mission_elapsed())
    )
}

/// The path and its progress, right under the mode: what an autonomous mode is doing.
fn navigation_rows(app: &App) -> Vec<Row> {
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
        rows.push(Row::new("Mission", state, Need::Must).wrapping(2));
        rows.push(Row::new("Why", reason, Need::High).wrapping(2));
        rows.push(
            Row::new(
                "Blocks",
                blocks_text(app, m.delivered(), m.known_blocks()),
                Need::High,
            )
            .wrapping(2),
        );
    }
    let controller = app.pilot().follower().controller().label();
    if let Some(f) = app.pilot().following() {
        rows.push(Row::new(
            "Path",
            format!("{:.2} m, {:.0} s left", f.remaining, f.eta),
            Need::High,
        ));
        rows.push(Row::new(
            "XTE",
            format!("{:+.1} cm  {controller}", f.cross_track * 100.0),
            Need::Low,
        ));
    } else if let Some(route) = app.pilot().route() {
        let state = if app.pilot().arrived() {
            "arrived at"
        } else {
            "to"
        };
        rows.push(
            Row::new(
                "Path",
                format!("{:.2} m {state} {}", route.plan.length, route.label),
                Need::High,
            )
            .wrapping(2),
        );
    }
    if let Some(progress) = app.pilot().waypoints().progress() {
        rows.push(Row::new("Route", progress, Need::High));
    }
    if let Some(c) = app.goal_cursor() {
        rows.push(Row::new(
            "Cursor",
            format!("{:6.2} {:6.2}  {controller}", c.x, c.y),
            Need::High,
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
    fn a_heading_that_rounds_to_zero_has_no_sign() {
        let text = pose_text(Pose2::new(-0.001, 0.5, -0.004));
        assert!(!text.contains('-'), "{text}");
    }
}
