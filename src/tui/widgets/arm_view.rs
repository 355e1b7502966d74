//! Gripper mode's side view of the arm, beside the map: the arm in its own plane (reach
//! across, height up) with its joints (`o`), links (`*`), tool (`T`) and the reachable
//! envelope (`.`, the circle the shoulder's links reach), above the joint angles, the
//! tool's pose, the jog speed and any warning (a joint near its limit, a singularity
//! near, a jog stopped at the edge).

use crate::app::App;
use crate::arm::kinematics::side_chain;
use crate::arm::{forward, manipulability, near_singular};
use crate::tui::theme::Theme;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::Line;

/// A joint within this of a limit is flagged, radians (5°).
const NEAR_LIMIT: f64 = 0.0873;

/// The panel's text, `width` columns at most; a warning wraps over up to three rows.
pub fn lines(app: &App, theme: Theme, width: usize) -> Vec<Line<'static>> {
    let Some(arm) = app.pilot().arm() else {
        return Vec::new();
    };
    let fit = |text: String, style| Line::styled(super::text::fit(&text, width), style);
    let q = arm.joints();
    let degrees: Vec<String> =
        q.0.iter()
            .map(|j| format!("{:.0}°", j.to_degrees() + 0.0))
            .collect();
    let tool = forward(&arm.config, &arm.target);
    let warning = warning(arm);
    let mut lines = vec![
        fit(format!("J {}", degrees.join(" ")), theme.value()),
        fit(
            format!(
                "tool r {:.3} z {:.3} p {:.0}°",
                tool.x.hypot(tool.y),
                tool.z,
                tool.pitch.to_degrees() + 0.0
            ),
            theme.value(),
        ),
        fit(
            format!(
                "jog {:.1} cm/s  gripper {}",
                arm.speed * 100.0,
                app.pilot().gripper().map_or("-", |g| g.label())
            ),
            theme.value(),
        ),
    ];
    // A warning says why in full, over up to three rows.
    match warning {
        Some(w) => lines.extend(
            super::text::wrap_rows(&w, width, 3)
                .into_iter()
                .map(|l| Line::styled(l, theme.alert())),
        ),
        None => lines.push(fit("ok".into(), theme.label())),
    }
    lines
}

/// The most pressing warning about the arm, if any.
fn warning(arm: &crate::pilot::arm::ArmPilot) -> Option<String> {
    if let Some(why) = &arm.at_edge {
        return Some(format!("stopped: {why}"));
    }
    let limits = &arm.config.limits;
    let joints = arm.target.0.iter().zip(limits.min.iter().zip(&limits.max));
    for (k, (q, (lo, hi))) in joints.enumerate() {
        if q - lo < NEAR_LIMIT || hi - q < NEAR_LIMIT {
            return Some(format!("joint {} near its limit", k + 1));
        }
    }
    near_singular(&arm.config, manipulability(&arm.config, &arm.target))
        .then(|| "near a singularity".to_string())
}

/// Draws the arm from the side into `area`.
pub fn drawing(app: &App, theme: Theme, area: Rect, buf: &mut Buffer) {
    let Some(arm) = app.pilot().arm() else {
        return;
    };
    if area.width < 4 || area.height < 3 {
        return;
    }
    let cfg = &arm.config;
    let reach: f64 = cfg.links.iter().sum();
    // Metres per column; rows are twice as tall. The view spans the reach forward and
    // back of the base and from the floor to above the shoulder's reach.
    let span_r = 2.0 * reach;
    let span_z = cfg.base_height + reach + 0.05;
    let scale = (span_r / f64::from(area.width)).max(span_z / (2.0 * f64::from(area.height)));
    let (r0, z_top) = (-reach, cfg.base_height + reach);
    let cell = |r: f64, z: f64| -> Option<(u16, u16)> {
        let c = ((r - r0) / scale).floor();
        let row = ((z_top - z) / (2.0 * scale)).floor();
        (c >= 0.0 && row >= 0.0 && c < f64::from(area.width) && row < f64::from(area.height))
            .then(|| (area.x + c as u16, area.y + row as u16))
    };
    let mut put = |r: f64, z: f64, glyph: char, style| {
        if let Some(at) = cell(r, z) {
            buf[at].set_char(glyph).set_style(style);
        }
    };
    // The envelope: the furthest the links reach from the shoulder.
    let n = 96;
    for k in 0..n {
        let a = std::f64::consts::TAU * f64::from(k) / f64::from(n);
        put(
            reach * a.cos(),
            cfg.base_height + reach * a.sin(),
            '.',
            theme.label(),
        );
    }
    // The floor.
    for c in 0..area.width {
        put(r0 + (f64::from(c) + 0.5) * scale, 0.0, '_', theme.label());
    }
    // The arm as asked, then as measured over it.
    let chain = side_chain(cfg, &arm.joints());
    for pair in chain.windows(2) {
        let ((ra, za), (rb, zb)) = (pair[0], pair[1]);
        let steps = ((rb - ra).hypot(zb - za) / (0.5 * scale)).ceil().max(1.0) as usize;
        for s in 0..=steps {
            let f = s as f64 / steps as f64;
            put(ra + f * (rb - ra), za + f * (zb - za), '*', theme.robot());
        }
    }
    for &(r, z) in &chain[1..4] {
        put(r, z, 'o', theme.robot());
    }
    let (rt, zt) = chain[4];
    put(rt, zt, 'T', theme.robot());
    put(0.0, 0.0, '#', theme.value());
}
