//! The fleet panel: one row per robot (name, link, mode, what it is doing, pose, speed,
//! last warning), the selected robot marked, at the bottom of the screen.

use super::{Fleet, Member};
use crate::app::LinkStatus;
use crate::app::log::Level;
use crate::pilot::mode::Mode;
use crate::tui::theme::Theme;
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph};

/// Rows the panel takes for `robots` robots on a `height`-row terminal: one per robot and
/// its border, at most a third of the screen (the list scrolls to keep the selected one).
pub fn rows_for(robots: usize, height: u16) -> u16 {
    // One robot (a ROS 2 console that may grow into a fleet) needs no panel.
    if robots < 2 {
        return 0;
    }
    let wanted = u16::try_from(robots).unwrap_or(u16::MAX).saturating_add(2);
    wanted.min((height / 3).max(3)).min(height)
}

/// What a robot is doing, in a few words: the e-stop, the mission's state, the path, or
/// the behaviour in control.
fn doing(m: &Member) -> String {
    let p = m.app.pilot();
    if p.estop() {
        return "E-STOP".into();
    }
    if let Some(mission) = p.mission().filter(|_| p.mode() == Mode::Exploration) {
        return mission.state_label();
    }
    if let Some(f) = p.following() {
        return format!("path, {:.1} m left", f.remaining);
    }
    match p.arbiter().winner() {
        Some((b, _)) => b.to_string(),
        None => "idle".into(),
    }
}

fn link(m: &Member) -> &'static str {
    match m.app.pilot().link_status() {
        LinkStatus::Ok => "ok",
        LinkStatus::Lost(_) if !m.app.pilot().link_ever_up() => "waiting",
        LinkStatus::Lost(_) => "LOST",
        LinkStatus::Back => "back",
    }
}

/// The newest warning or error in the robot's log.
fn last_warning(m: &Member) -> String {
    (m.app.log_book().problems().last()).map_or(String::new(), |e| e.text.clone())
}

/// One robot's row, cut to `width` characters.
pub fn row_text(m: &Member, number: usize, selected: bool, width: usize) -> String {
    let p = m.app.pilot();
    let pose = p.estimated_pose();
    let speed = p.measured();
    let mark = if selected { '>' } else { ' ' };
    let mut doing = doing(m);
    doing.truncate(doing.char_indices().nth(24).map_or(doing.len(), |(i, _)| i));
    let text = format!(
        "{mark}{number:>2} {:<10} {:<7} {:<10} {doing:<24} {:6.2} {:6.2} {:4.0}° {:+.2} m/s  {}",
        m.name,
        link(m),
        p.mode().label(),
        pose.x + 0.0,
        pose.y + 0.0,
        pose.theta.to_degrees().round() + 0.0,
        speed.linear + 0.0,
        last_warning(m),
    );
    text.chars().take(width).collect()
}

/// The panel in `area`: a bordered list, the selected robot highlighted.
pub fn render(fleet: &Fleet, theme: Theme, area: Rect, frame: &mut Frame) {
    let shown = usize::from(area.height.saturating_sub(2));
    let first = (fleet.selected() + 1).saturating_sub(shown);
    let width = usize::from(area.width.saturating_sub(2));
    let lines: Vec<Line> = (fleet.members().iter().enumerate())
        .skip(first)
        .take(shown)
        .map(|(i, m)| {
            let selected = i == fleet.selected();
            let lost = matches!(m.app.pilot().link_status(), LinkStatus::Lost(_));
            let style = match (selected, lost) {
                (_, true) => theme.level(Level::Warn),
                (true, false) => theme.mode(),
                (false, false) => theme.value(),
            };
            Line::from(Span::styled(row_text(m, i + 1, selected, width), style))
        })
        .collect();
    let title = format!(
        " Fleet: {} robots · ctrl-n/ctrl-p select · X stops all ",
        fleet.members().len()
    );
    let block = Block::bordered().title(title).border_style(theme.border());
    frame.render_widget(Paragraph::new(lines).block(block), area);
}
