//! The replay's time bar: playing or paused, speed, time, progress, the view, the keys.

use crate::app::log::format_time;
use crate::replay::playback::Playback;
use crate::tui::theme::Theme;
use ratatui::text::{Line, Span};

/// The keys, shortened as the bar narrows.
const KEYS: [&str; 2] = [
    "space play/pause  ,/. step  ←/→ 5 s  [/] speed  1-9 jump  : time  r view  q quit",
    "space ,/. ←/→ [/] 1-9 : r q",
];

pub fn line(p: &Playback, theme: Theme, width: usize) -> Line<'static> {
    let (start, end) = p.span();
    let state = if p.paused { "❚❚" } else { "▶" };
    let speed = if p.speed < 1.0 {
        format!("{}x", p.speed)
    } else {
        format!("{:.0}x", p.speed)
    };
    let time = format!(
        "{} / {}",
        format_time(p.position() - start),
        format_time(end - start)
    );
    let head = format!(" {state} {speed:>5}  {time}  ");
    let view = format!("  {}  ", p.view.label());
    if let Some(text) = &p.prompt {
        let line = format!(" go to (seconds or m:ss): {text}█  enter goes, esc cancels");
        return Line::from(Span::styled(line, theme.value()));
    }
    let mut tail = p
        .refusal
        .as_ref()
        .map(|r| format!("{r}  "))
        .unwrap_or_default();
    let used = head.chars().count() + view.chars().count();
    let keys = KEYS
        .iter()
        .find(|k| used + 12 + k.chars().count() <= width)
        .copied()
        .unwrap_or("");
    tail += keys;
    let room = width.saturating_sub(used + tail.chars().count() + 2).max(4);
    let done = if end > start {
        ((p.position() - start) / (end - start)).clamp(0.0, 1.0)
    } else {
        1.0
    };
    let filled = ((done * room as f64).round() as usize).min(room);
    let bar = format!("[{}{}]", "█".repeat(filled), "░".repeat(room - filled));
    Line::from(vec![
        Span::styled(head, theme.mode()),
        Span::styled(bar, theme.path()),
        Span::styled(view, theme.value()),
        Span::styled(tail, theme.label()),
    ])
}
