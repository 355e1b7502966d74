//! The map: the occupancy grid as ASCII (or braille), markers, blocks and the robot.

use crate::app::App;
use crate::geometry::{Point2, Pose2};
use crate::map::costmap::{Costmap, Shade};
use crate::map::grid::{OCCUPIED, OccupancyGrid};
use crate::perception::markers::MarkerCategory;
use crate::tui::theme::{Theme, marker_glyph};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Style;

pub use super::viewport::Viewport;

/// Grids the viewport can cut into screen cells.
trait CellRanges {
    fn columns_in(&self, x0: f64, x1: f64) -> Option<(usize, usize)>;
    fn rows_in(&self, y0: f64, y1: f64) -> Option<(usize, usize)>;
}

impl CellRanges for OccupancyGrid {
    fn columns_in(&self, x0: f64, x1: f64) -> Option<(usize, usize)> {
        OccupancyGrid::columns_in(self, x0, x1)
    }
    fn rows_in(&self, y0: f64, y1: f64) -> Option<(usize, usize)> {
        OccupancyGrid::rows_in(self, y0, y1)
    }
}

impl CellRanges for Costmap {
    fn columns_in(&self, x0: f64, x1: f64) -> Option<(usize, usize)> {
        Costmap::columns_in(self, x0, x1)
    }
    fn rows_in(&self, y0: f64, y1: f64) -> Option<(usize, usize)> {
        Costmap::rows_in(self, y0, y1)
    }
}

/// Draws the map into `area` of `buf`.
pub fn render(app: &App, theme: Theme, area: Rect, buf: &mut Buffer) {
    if area.width == 0 || area.height == 0 {
        return;
    }
    let scale = app.view().scale(app.fitted_scale());
    let vp = Viewport::new(area, app.map_center(), scale);
    let costmap = app.pilot().belief().costmap();
    if app.view().braille {
        if app.view().show_truth
            && let Some(grid) = app.world_grid()
        {
            draw_grid_braille(grid, &vp, theme.truth(), buf);
        }
        draw_costmap_braille(costmap, &vp, theme.occupied(), buf);
    } else {
        if app.view().show_truth
            && let Some(grid) = app.world_grid()
        {
            draw_grid_ascii(grid, &vp, theme, buf);
        }
        draw_costmap_ascii(costmap, &vp, theme, buf);
    }
    if app.view().show_truth {
        draw_world_objects(app, &vp, theme, buf);
    }
    super::particles::render(app, &vp, theme, buf);
    super::sensing::render(app, &vp, theme, buf);
    super::graph::render(app, &vp, theme, buf);
    super::tag_graph::render(app, &vp, theme, buf);
    super::path::render(app, &vp, theme, buf);
    super::explore::render(app, &vp, theme, buf);
    super::beliefs::render(app, &vp, theme, buf);
    if app.view().show_truth
        && let Some(truth) = app.true_pose()
    {
        draw_robot(truth, 'o', &vp, theme.truth(), buf);
    }
    super::filter_zones::render(app, &vp, theme, buf);
    super::sensing::footprint(app, &vp, theme, buf);
    super::zones::render(app, &vp, theme, buf);
    // A fleet's other robots by their numbers (past 9: their names' first letters).
    for mark in app.fleet_marks() {
        let body = char::from_digit(mark.number as u32, 10)
            .filter(|_| mark.number < 10)
            .or_else(|| mark.name.chars().next())
            .unwrap_or('?');
        draw_robot(mark.pose, body, &vp, theme.value(), buf);
    }
    draw_robot(app.pilot().estimated_pose(), '@', &vp, theme.robot(), buf);
    super::path::cursor(app, &vp, theme, buf);
}

/// The twin's true walls, dimmed, under the robot's own map (`g`).
fn draw_grid_ascii(grid: &OccupancyGrid, vp: &Viewport, theme: Theme, buf: &mut Buffer) {
    let occupied = super::beliefs::truth_style(theme.occupied());
    draw_ascii(grid, vp, buf, |cols, rows| {
        (grid.max_in_cells(cols, rows) >= OCCUPIED / 2).then_some(('#', occupied))
    });
}

/// A recorded occupancy grid: '#' occupied, '.' known and free, unknown left blank.
pub fn draw_occupancy_ascii(grid: &OccupancyGrid, vp: &Viewport, theme: Theme, buf: &mut Buffer) {
    draw_ascii(grid, vp, buf, |cols, rows| {
        let worst = grid.max_in_cells(cols, rows);
        if worst >= OCCUPIED / 2 {
            Some(('#', theme.occupied()))
        } else {
            (worst >= 0).then_some(('.', theme.free()))
        }
    });
}

/// One glyph per screen cell, chosen by `look` from the grid cells under it.
fn draw_ascii(
    grid: &dyn CellRanges,
    vp: &Viewport,
    buf: &mut Buffer,
    look: impl Fn((usize, usize), (usize, usize)) -> Option<(char, Style)>,
) {
    let (cols, rows) = grid_spans(vp, grid, 1, 1);
    for (r, row_span) in rows.iter().enumerate() {
        let Some(row_span) = *row_span else { continue };
        for (c, col_span) in cols.iter().enumerate() {
            let Some(col_span) = *col_span else { continue };
            if let Some((glyph, style)) = look(col_span, row_span) {
                buf[(vp.area.x + c as u16, vp.area.y + r as u16)]
                    .set_char(glyph)
                    .set_style(style);
            }
        }
    }
}

/// Braille: each cell holds 2 x 4 dots, so the map gets twice the columns and four
/// times the rows of the ASCII view (the technique termviz uses).
fn draw_grid_braille(grid: &OccupancyGrid, vp: &Viewport, style: Style, buf: &mut Buffer) {
    let (cols, rows) = grid_spans(vp, grid, 2, 4);
    let occupied = |c: usize, r: usize| match (cols[c], rows[r]) {
        (Some(cs), Some(rs)) => grid.max_in_cells(cs, rs) >= OCCUPIED / 2,
        _ => false,
    };
    draw_braille_dots(occupied, vp, style, buf);
}

/// The robot's map as ASCII: '#' lethal, ':' seed 001's 0.7 ring, '.' known and passable.
fn draw_costmap_ascii(map: &Costmap, vp: &Viewport, theme: Theme, buf: &mut Buffer) {
    draw_ascii(map, vp, buf, |cols, rows| {
        match map.worst_in_cells(cols, rows) {
            Shade::Lethal => Some(('#', theme.occupied())),
            Shade::Inflated => Some((':', theme.inflated())),
            Shade::Near | Shade::Free => Some(('.', theme.free())),
            Shade::Unknown => None,
        }
    });
}

/// The robot's map as braille dots: lethal cells only.
fn draw_costmap_braille(map: &Costmap, vp: &Viewport, style: Style, buf: &mut Buffer) {
    let (cols, rows) = grid_spans(vp, map, 2, 4);
    let lethal = |c: usize, r: usize| match (cols[c], rows[r]) {
        (Some(cs), Some(rs)) => map.worst_in_cells(cs, rs) == Shade::Lethal,
        _ => false,
    };
    draw_braille_dots(lethal, vp, style, buf);
}

/// Sets the braille dots where `on(sub_column, sub_row)`, over what is already drawn.
fn draw_braille_dots(
    on: impl Fn(usize, usize) -> bool,
    vp: &Viewport,
    style: Style,
    buf: &mut Buffer,
) {
    // Unicode braille: dot (column, row) -> bit, rows top to bottom.
    const BITS: [[u32; 4]; 2] = [[0x01, 0x02, 0x04, 0x40], [0x08, 0x10, 0x20, 0x80]];
    let occupied = on;
    for r in 0..usize::from(vp.area.height) {
        for c in 0..usize::from(vp.area.width) {
            let mut bits = 0;
            for (dx, column) in BITS.iter().enumerate() {
                for (dy, bit) in column.iter().enumerate() {
                    if occupied(2 * c + dx, 4 * r + dy) {
                        bits |= bit;
                    }
                }
            }
            if bits == 0 {
                continue;
            }
            let cell = &mut buf[(vp.area.x + c as u16, vp.area.y + r as u16)];
            // Merge with dots already there (the true walls under the robot's map).
            let old = cell.symbol().chars().next().map_or(0, u32::from);
            if (0x2800..=0x28ff).contains(&old) {
                bits |= old - 0x2800;
            }
            if let Some(ch) = char::from_u32(0x2800 + bits) {
                cell.set_char(ch).set_style(style);
            }
        }
    }
}

fn put(buf: &mut Buffer, vp: &Viewport, p: Point2, glyph: char, style: Style) {
    if let Some(cell) = vp.cell(p) {
        buf[cell].set_char(glyph).set_style(style);
    }
}

/// Markers by category, blocks where they are now; markers in view of the camera reversed.
fn draw_world_objects(app: &App, vp: &Viewport, theme: Theme, buf: &mut Buffer) {
    let Some(twin) = app.link().ground_truth() else {
        return;
    };
    let seen = app.in_view();
    let block_ids: Vec<u32> = twin.blocks().iter().flat_map(|b| b.markers).collect();
    for m in twin
        .world()
        .markers
        .iter()
        .filter(|m| !block_ids.contains(&m.id))
    {
        let category = MarkerCategory::of(m.id);
        let mut style = super::beliefs::truth_style(theme.marker(category));
        if seen.contains(&m.id) {
            style = style.add_modifier(ratatui::style::Modifier::REVERSED);
        }
        put(buf, vp, m.position, marker_glyph(category), style);
    }
    for b in twin.blocks() {
        let category = MarkerCategory::of(b.markers[0]);
        let mut style = theme.marker(category);
        if b.markers.iter().any(|id| seen.contains(id)) {
            style = style.add_modifier(ratatui::style::Modifier::REVERSED);
        }
        put(buf, vp, b.pose.position(), marker_glyph(category), style);
    }
}

/// The robot as `body` with a heading tick in the neighbouring cell it faces.
pub fn draw_robot(pose: Pose2, body: char, vp: &Viewport, style: Style, buf: &mut Buffer) {
    let Some((cx, cy)) = vp.cell(pose.position()) else {
        return;
    };
    // Heading in screen cells: rows are twice as tall as columns are wide.
    let screen_angle = (pose.theta.sin() / 2.0).atan2(pose.theta.cos());
    let octant = ((screen_angle / std::f64::consts::FRAC_PI_4).round() as i32).rem_euclid(8);
    let (dx, dy, tick) = match octant {
        0 => (1, 0, '-'),
        1 => (1, -1, '/'),
        2 => (0, -1, '|'),
        3 => (-1, -1, '\\'),
        4 => (-1, 0, '-'),
        5 => (-1, 1, '/'),
        6 => (0, 1, '|'),
        _ => (1, 1, '\\'),
    };
    let (tx, ty) = (i32::from(cx) + dx, i32::from(cy) + dy);
    let a = vp.area;
    if tx >= i32::from(a.x)
        && ty >= i32::from(a.y)
        && tx < i32::from(a.x + a.width)
        && ty < i32::from(a.y + a.height)
    {
        buf[(tx as u16, ty as u16)].set_char(tick).set_style(style);
    }
    buf[(cx, cy)].set_char(body).set_style(style);
}

/// Grid index ranges under each of `per_col` sub-columns of every column and `per_row`
/// sub-rows of every row, computed once per frame rather than once per cell.
#[allow(clippy::type_complexity)]
fn grid_spans(
    vp: &Viewport,
    grid: &dyn CellRanges,
    per_col: u16,
    per_row: u16,
) -> (Vec<Option<(usize, usize)>>, Vec<Option<(usize, usize)>>) {
    let dx = vp.scale / f64::from(per_col);
    let dy = 2.0 * vp.scale / f64::from(per_row);
    let cols = (0..vp.area.width * per_col)
        .map(|i| {
            let x0 = vp.left + f64::from(i) * dx;
            grid.columns_in(x0, x0 + dx)
        })
        .collect();
    let rows = (0..vp.area.height * per_row)
        .map(|i| {
            let y1 = vp.top - f64::from(i) * dy;
            grid.rows_in(y1 - dy, y1)
        })
        .collect();
    (cols, rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn viewport_maps_centre_and_corners() {
        let vp = Viewport::new(Rect::new(10, 5, 40, 20), Point2::new(0.0, 0.0), 0.1);
        assert_eq!(vp.cell(Point2::new(0.0, 0.0)), Some((30, 15)));
        assert_eq!(vp.cell(Point2::new(-1.99, 1.99)), Some((10, 5)));
        assert_eq!(vp.cell(Point2::new(2.01, 0.0)), None);
    }
}
