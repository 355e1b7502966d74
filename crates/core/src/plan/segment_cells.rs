//! Every cell a straight segment touches: Amanatides & Woo's grid traversal ("A Fast Voxel
//! Traversal Algorithm for Ray Tracing", Eurographics 1987), made a supercover: where the
//! segment passes exactly through a cell corner, both cells beside the corner are visited too.

use crate::geometry::Point2;
use crate::map::costmap::Costmap;

/// Calls `visit(cx, cy)` for each cell the segment a-b touches, in order, until it returns
/// false; returns whether the traversal ran to the end. Both ends must lie on the map.
pub fn for_each_cell(
    map: &Costmap,
    a: Point2,
    b: Point2,
    mut visit: impl FnMut(usize, usize) -> bool,
) -> bool {
    let r = map.resolution;
    // Positions in cell units.
    let (ax, ay) = ((a.x - map.origin.x) / r, (a.y - map.origin.y) / r);
    let (bx, by) = ((b.x - map.origin.x) / r, (b.y - map.origin.y) / r);
    let clamp_x = |v: f64| (v.floor().max(0.0) as usize).min(map.width - 1) as i64;
    let clamp_y = |v: f64| (v.floor().max(0.0) as usize).min(map.height - 1) as i64;
    let (mut cx, mut cy) = (clamp_x(ax), clamp_y(ay));
    let (ex, ey) = (clamp_x(bx), clamp_y(by));
    let (dx, dy) = (bx - ax, by - ay);
    let step_x: i64 = if dx > 0.0 { 1 } else { -1 };
    let step_y: i64 = if dy > 0.0 { 1 } else { -1 };
    // Amanatides & Woo: t of the first vertical/horizontal cell boundary, and t per cell.
    let t_delta_x = if dx != 0.0 {
        1.0 / dx.abs()
    } else {
        f64::INFINITY
    };
    let t_delta_y = if dy != 0.0 {
        1.0 / dy.abs()
    } else {
        f64::INFINITY
    };
    let next_x = if dx > 0.0 { cx as f64 + 1.0 } else { cx as f64 };
    let next_y = if dy > 0.0 { cy as f64 + 1.0 } else { cy as f64 };
    let mut t_max_x = if dx != 0.0 {
        (next_x - ax) / dx
    } else {
        f64::INFINITY
    };
    let mut t_max_y = if dy != 0.0 {
        (next_y - ay) / dy
    } else {
        f64::INFINITY
    };
    let inside = |x: i64, y: i64| x >= 0 && y >= 0 && x < map.width as i64 && y < map.height as i64;
    let limit = (ex - cx).abs() + (ey - cy).abs() + 2;
    if !visit(cx as usize, cy as usize) {
        return false;
    }
    for _ in 0..limit {
        if cx == ex && cy == ey {
            break;
        }
        let tie = (t_max_x - t_max_y).abs() < 1e-9;
        if tie {
            // Through a corner: touch both neighbours, then step diagonally.
            for (x, y) in [(cx + step_x, cy), (cx, cy + step_y)] {
                if inside(x, y) && !visit(x as usize, y as usize) {
                    return false;
                }
            }
            cx += step_x;
            cy += step_y;
            t_max_x += t_delta_x;
            t_max_y += t_delta_y;
        } else if t_max_x < t_max_y {
            cx += step_x;
            t_max_x += t_delta_x;
        } else {
            cy += step_y;
            t_max_y += t_delta_y;
        }
        if !inside(cx, cy) {
            break; // rounding carried the walk off the map: finish at the end cell
        }
        if !visit(cx as usize, cy as usize) {
            return false;
        }
    }
    if (cx, cy) != (ex, ey) {
        return visit(ex as usize, ey as usize);
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cells(a: Point2, b: Point2) -> Vec<(usize, usize)> {
        let map = Costmap::new(10, 10, 1.0, Point2::new(0.0, 0.0), 0);
        let mut out = vec![];
        for_each_cell(&map, a, b, |x, y| {
            out.push((x, y));
            true
        });
        out
    }

    #[test]
    fn a_shallow_segment_touches_each_cell_it_crosses() {
        let c = cells(Point2::new(0.5, 0.5), Point2::new(3.5, 1.7));
        assert_eq!(c, vec![(0, 0), (1, 0), (1, 1), (2, 1), (3, 1)]);
    }

    #[test]
    fn an_exact_diagonal_touches_the_cells_beside_each_corner() {
        let c = cells(Point2::new(0.5, 0.5), Point2::new(2.5, 2.5));
        assert_eq!(
            c,
            vec![(0, 0), (1, 0), (0, 1), (1, 1), (2, 1), (1, 2), (2, 2)]
        );
    }

    #[test]
    fn a_segment_inside_one_cell_visits_it_once() {
        assert_eq!(
            cells(Point2::new(4.2, 4.2), Point2::new(4.8, 4.3)),
            vec![(4, 4)]
        );
    }
}
