//! Route mode's panel (seed 003): what the run is doing, the tags in view and the last
//! pose reset, over the list of the tag map's tasks and tags to choose from; and its rows
//! of the status panel.

use super::rows::{Need, Row};
use super::text;
use crate::app::App;
use crate::pilot::mode::Mode;
use crate::pilot::tag_route::{TagGoal, TagRouting};
use crate::tui::theme::Theme;
use ratatui::text::Line;

/// What to pass for route mode when no tag map is laid.
pub const NO_MAP: &str =
    "no tag map: start navdeck with --tags FILE (e.g. --tags maps/tag_warehouse.yaml)";

/// The panel's title.
pub const TITLE: &str = " Route (i): ↑↓ choose, enter drives ";

/// The panel's lines for `width` columns and `rows` rows: the run's state, then as
/// much of the list round the chosen row as fits.
pub fn lines(app: &App, theme: Theme, width: usize, rows: usize) -> Vec<Line<'static>> {
    let routing = app.pilot().tag_route();
    if routing.map().is_none() {
        return text::wrap(NO_MAP, width)
            .into_iter()
            .map(|l| Line::styled(l, theme.alert()))
            .collect();
    }
    let mut out: Vec<Line<'static>> = state_texts(routing)
        .into_iter()
        .map(|(alert, t)| {
            let style = if alert { theme.alert() } else { theme.value() };
            Line::styled(text::fit(&t, width), style)
        })
        .collect();
    let choices = app.route_choices();
    let room = rows.saturating_sub(out.len()).max(1);
    let chosen = app.route_pick().min(choices.len().saturating_sub(1));
    let first = chosen
        .saturating_sub(room / 2)
        .min(choices.len().saturating_sub(room));
    for (i, goal) in choices.iter().enumerate().skip(first).take(room) {
        let mark = if i == chosen { '>' } else { ' ' };
        let row = format!("{mark} {}", choice_text(app, goal));
        let style = if i == chosen {
            theme.mode()
        } else {
            theme.label()
        };
        out.push(Line::styled(text::fit(&row, width), style));
    }
    out
}

/// A list row: "task task1: 508 101 … (6 tags)", "tag 205 (zone B, shelf)".
fn choice_text(app: &App, goal: &TagGoal) -> String {
    let Some(map) = app.pilot().tag_route().map() else {
        return goal.label();
    };
    match goal {
        TagGoal::Task(name) => {
            let points = map.tasks.get(name).map_or(0, Vec::len);
            format!("task {name} ({points} waypoints)")
        }
        TagGoal::Tag(id) => match map.tags.get(id) {
            Some(t) => format!("tag {id} (zone {}, {:?})", t.zone.label(), t.kind).to_lowercase(),
            None => goal.label(),
        },
    }
}

/// The run's state as lines, each with whether it is an alert.
fn state_texts(routing: &TagRouting) -> Vec<(bool, String)> {
    let mut out = vec![(false, goal_and_phase(routing))];
    if let Some(outcome) = routing.outcome().filter(|_| !routing.driving()) {
        out.push((!outcome.contains(" done"), outcome.to_string()));
    }
    out.push((
        false,
        format!(
            "next tag {}  seen {}",
            next_text(routing),
            seen_text(routing)
        ),
    ));
    out.push((false, format!("reset {}", reset_text(routing))));
    if let Some(run) = routing.run().filter(|r| !r.blocked_edges().is_empty()) {
        let edges: Vec<String> = (run.blocked_edges().iter())
            .map(|(a, b)| format!("{a}-{b}"))
            .collect();
        out.push((true, format!("blocked {}", edges.join(" "))));
    }
    out
}

/// "task task1: driving leg 2 (101 → 102)", or the phase alone with no goal yet.
fn goal_and_phase(routing: &TagRouting) -> String {
    match routing.goal() {
        Some(goal) => format!("{}: {}", goal.label(), routing.phase_text()),
        None => routing.phase_text(),
    }
}

fn next_text(routing: &TagRouting) -> String {
    routing.next_tag().map_or("-".into(), |t| t.to_string())
}

/// The tags in the newest frame, by id.
fn seen_text(routing: &TagRouting) -> String {
    let ids: Vec<String> = routing.seen().iter().map(|s| s.id.to_string()).collect();
    if ids.is_empty() {
        "none".into()
    } else {
        ids.join(" ")
    }
}

/// "tag 101 at 12.3 s (3.00, 0.00 0°), 57 so far".
fn reset_text(routing: &TagRouting) -> String {
    match routing.last_reset() {
        Some(r) => {
            // Rounded first, then + 0.0: a value that rounds to zero shows no sign.
            let round = |v: f64, unit: f64| (v / unit).round() * unit + 0.0;
            format!(
                "tag {} at {:.1} s ({:.2}, {:.2} {:.0}°), {} so far",
                r.tag,
                r.t,
                round(r.pose.x, 0.01),
                round(r.pose.y, 0.01),
                round(r.pose.theta.to_degrees(), 1.0),
                routing.resets()
            )
        }
        None => "none yet".into(),
    }
}

/// Route mode's rows of the status panel: in route mode, or while a run is under way.
pub fn status_rows(app: &App) -> Vec<Row> {
    let routing = app.pilot().tag_route();
    let in_mode = app.pilot().mode() == Mode::Route;
    if !in_mode && routing.run().is_none() {
        return Vec::new();
    }
    if routing.map().is_none() {
        return vec![Row::new("Route", NO_MAP, Need::Must).wrapping(3)];
    }
    let paused = if in_mode {
        ""
    } else {
        " (paused: i drives on)"
    };
    let phase = format!("{}{paused}", goal_and_phase(routing));
    let mut rows = vec![Row::new("Route", phase, Need::Must).wrapping(2)];
    if let (Some((leg, from, to)), Some(run)) = (routing.current_leg(), routing.run()) {
        let legs = run.route().legs.len();
        let text = format!("{} of {legs}: {from} → {to}", leg + 1);
        rows.push(Row::new("Leg", text, Need::High));
    }
    if let Some(outcome) = routing.outcome().filter(|_| !routing.driving()) {
        rows.push(Row::new("Outcome", outcome, Need::High).wrapping(3));
    }
    rows.push(Row::new(
        "Next",
        format!("tag {}", next_text(routing)),
        Need::High,
    ));
    rows.push(Row::new(
        "Tags",
        format!("in view {}", seen_text(routing)),
        Need::Some,
    ));
    rows.push(Row::new("Reset", reset_text(routing), Need::Some).wrapping(2));
    rows
}
