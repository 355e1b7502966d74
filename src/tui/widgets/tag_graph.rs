//! The tag graph over the map (seed 003's tag map, with `--tags`): each tag a node
//! (`□`, the dock `D`), each edge a line (`- / | \`), the route being driven in double
//! lines (`═ ║ ╱ ╲`) with its tags `■`, and edges found blocked as `×`.

use super::beliefs::set_dot;
use super::viewport::Viewport;
use crate::app::App;
use crate::geometry::Point2;
use crate::tags::TagMap;
use crate::tui::theme::Theme;
use ratatui::buffer::Buffer;
use ratatui::style::{Modifier, Style};

/// How an edge is drawn.
#[derive(Clone, Copy, PartialEq, Eq)]
enum EdgeLook {
    Plain,
    OnRoute,
    Blocked,
}

/// The tag graph, when a tag map is laid.
pub fn render(app: &App, vp: &Viewport, theme: Theme, buf: &mut Buffer) {
    let routing = app.pilot().tag_route();
    let Some(map) = routing.map() else {
        return;
    };
    let braille = app.view().braille;
    let run = routing.run().filter(|_| routing.driving());
    let route_tags: &[u32] = run.map_or(&[], |r| &r.route().tags);
    let on_route = |a: u32, b: u32| route_tags.windows(2).any(|w| w == [a, b] || w == [b, a]);
    let blocked = |a: u32, b: u32| {
        (routing.run().map_or(&[][..], |r| r.blocked_edges()))
            .iter()
            .any(|&(x, y)| (x, y) == (a, b) || (x, y) == (b, a))
    };
    // Plain edges first, so that the route and blocked edges stay visible over them.
    let mut edges: Vec<(u32, u32, EdgeLook)> = (map.edges.iter())
        .flat_map(|(&from, list)| list.iter().map(move |e| (from, e.to)))
        .map(|(a, b)| {
            let look = match (blocked(a, b), on_route(a, b)) {
                (true, _) => EdgeLook::Blocked,
                (false, true) => EdgeLook::OnRoute,
                _ => EdgeLook::Plain,
            };
            (a, b, look)
        })
        .collect();
    edges.sort_by_key(|e| e.2 != EdgeLook::Plain);
    for (a, b, look) in edges {
        let (Some(a), Some(b)) = (at(map, a), at(map, b)) else {
            continue;
        };
        let style = match look {
            EdgeLook::Plain => theme.graph(),
            EdgeLook::OnRoute => theme.path(),
            EdgeLook::Blocked => theme.alert(),
        };
        let glyph = edge_glyph(a, b, look);
        let step = if braille {
            vp.scale / 4.0
        } else {
            vp.scale / 2.0
        };
        let n = ((a.distance(b) / step).ceil() as usize).clamp(1, 4000);
        for k in 1..n {
            let f = k as f64 / n as f64;
            let p = Point2::new(a.x + f * (b.x - a.x), a.y + f * (b.y - a.y));
            if braille && look != EdgeLook::Blocked {
                set_dot(p, vp, style, buf);
            } else {
                mark(p, glyph, vp, style, buf);
            }
        }
    }
    let next = routing.next_tag();
    for (&id, tag) in &map.tags {
        let Some(cell) = vp.cell(Point2::new(tag.x, tag.y)) else {
            continue;
        };
        let glyph = match (id == map.dock, route_tags.contains(&id)) {
            (true, _) => 'D',
            (false, true) => '■',
            (false, false) => '□',
        };
        let mut style = if route_tags.contains(&id) {
            theme.path()
        } else {
            theme.graph()
        };
        if next == Some(id) {
            style = style.add_modifier(Modifier::BOLD | Modifier::REVERSED);
        }
        buf[cell].set_char(glyph).set_style(style);
    }
}

fn at(map: &TagMap, id: u32) -> Option<Point2> {
    map.tags.get(&id).map(|t| Point2::new(t.x, t.y))
}

/// The glyph of an edge from `a` to `b` on screen, where a row is twice a column's
/// height: a line for a plain edge, a double line on the route, `×` when blocked.
fn edge_glyph(a: Point2, b: Point2, look: EdgeLook) -> char {
    if look == EdgeLook::Blocked {
        return '×';
    }
    let (dx, dy) = (b.x - a.x, (b.y - a.y) / 2.0);
    let angle = dy.atan2(dx).to_degrees().rem_euclid(180.0);
    let lines = match look {
        EdgeLook::OnRoute => ['═', '╱', '║', '╲'],
        _ => ['-', '/', '|', '\\'],
    };
    match angle {
        a if !(22.5..157.5).contains(&a) => lines[0],
        a if a < 67.5 => lines[1],
        a if a < 112.5 => lines[2],
        _ => lines[3],
    }
}

/// `glyph` at `p` over free, unknown or line cells (walls and the robot keep theirs).
fn mark(p: Point2, glyph: char, vp: &Viewport, style: Style, buf: &mut Buffer) {
    if let Some(cell) = vp.cell(p) {
        let cell = &mut buf[cell];
        let free = matches!(
            cell.symbol(),
            " " | "." | ":" | "·" | "'" | "-" | "/" | "|" | "\\" | "═" | "║" | "╱" | "╲"
        );
        if free {
            cell.set_char(glyph).set_style(style);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn route_edges_are_doubled_and_blocked_ones_crossed() {
        let o = Point2::new(0.0, 0.0);
        let east = Point2::new(1.0, 0.0);
        let north = Point2::new(0.0, 1.0);
        assert_eq!(edge_glyph(o, east, EdgeLook::Plain), '-');
        assert_eq!(edge_glyph(o, east, EdgeLook::OnRoute), '═');
        assert_eq!(edge_glyph(o, north, EdgeLook::OnRoute), '║');
        assert_eq!(edge_glyph(o, north, EdgeLook::Blocked), '×');
    }
}
