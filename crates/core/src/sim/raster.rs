//! Static geometry burnt into an occupancy grid, for drawing the map and for planners.

use super::World;
use super::shapes::rect_contains;
use crate::geometry::{Point2, Segment};
use crate::map::grid::{FREE, OCCUPIED, OccupancyGrid};

/// Walls and obstacles OCCUPIED, the rest of the world FREE; origin at the lower-left corner.
pub fn rasterize(world: &World, resolution: f64) -> OccupancyGrid {
    let origin = Point2::new(-world.width / 2.0, -world.height / 2.0);
    if !(resolution.is_finite() && resolution > 0.0) {
        return OccupancyGrid::new(0, 0, resolution, origin, FREE);
    }
    let cols = (world.width / resolution - 1e-9).ceil().max(1.0) as usize;
    let rows = (world.height / resolution - 1e-9).ceil().max(1.0) as usize;
    let mut grid = OccupancyGrid::new(cols, rows, resolution, origin, FREE);
    for wall in &world.walls {
        trace(&mut grid, *wall);
    }
    for o in &world.obstacles {
        fill_rect(&mut grid, o.pose, o.width, o.height);
    }
    grid
}

/// Cell indices of a point, clamped onto the grid (points on the far edge land in the
/// last cell), plus the point's offset inside that cell in cell units.
fn cell(grid: &OccupancyGrid, p: Point2) -> ([i64; 2], [f64; 2]) {
    let fx = ((p.x - grid.origin.x) / grid.resolution).clamp(0.0, grid.width as f64 - 1e-9);
    let fy = ((p.y - grid.origin.y) / grid.resolution).clamp(0.0, grid.height as f64 - 1e-9);
    ([fx.floor() as i64, fy.floor() as i64], [fx, fy])
}

/// Marks every cell the segment passes through, stepping one axis at a time so the trace
/// is 4-connected and nothing can leak diagonally (Amanatides & Woo, "A Fast Voxel
/// Traversal Algorithm for Ray Tracing", Eurographics 1987).
fn trace(grid: &mut OccupancyGrid, s: Segment) {
    let (start, fa) = cell(grid, s.a);
    let (end, fb) = cell(grid, s.b);
    let (dx, dy) = (fb[0] - fa[0], fb[1] - fa[1]);
    let step = [end[0].cmp(&start[0]) as i64, end[1].cmp(&start[1]) as i64];
    // Parameter t in [0, 1] along the segment at which the next x / y cell border is crossed.
    let first_border = |f: f64, c: i64, st: i64, d: f64| {
        if st == 0 {
            f64::INFINITY
        } else {
            let border = if st > 0 { c as f64 + 1.0 } else { c as f64 };
            (border - f) / d
        }
    };
    let delta = [1.0 / dx.abs(), 1.0 / dy.abs()];
    let mut t_max = [
        first_border(fa[0], start[0], step[0], dx),
        first_border(fa[1], start[1], step[1], dy),
    ];
    let mut c = start;
    let budget = (end[0] - start[0]).abs() + (end[1] - start[1]).abs();
    grid.set(c[0] as usize, c[1] as usize, OCCUPIED);
    for _ in 0..budget {
        // Step the axis whose border comes first, unless that axis is already done.
        let x_done = c[0] == end[0];
        let y_done = c[1] == end[1];
        let axis = if x_done {
            1
        } else if y_done || t_max[0] < t_max[1] {
            0
        } else {
            1
        };
        c[axis] += step[axis];
        t_max[axis] += delta[axis];
        grid.set(c[0] as usize, c[1] as usize, OCCUPIED);
    }
}

/// Marks the cells whose centres lie inside a rotated rectangle.
fn fill_rect(grid: &mut OccupancyGrid, pose: crate::geometry::Pose2, w: f64, h: f64) {
    let reach = w.hypot(h) / 2.0;
    let (lo, _) = cell(grid, Point2::new(pose.x - reach, pose.y - reach));
    let (hi, _) = cell(grid, Point2::new(pose.x + reach, pose.y + reach));
    for cy in lo[1]..=hi[1] {
        for cx in lo[0]..=hi[0] {
            let (cx, cy) = (cx as usize, cy as usize);
            if rect_contains(pose, w, h, grid.center_of(cx, cy)) {
                grid.set(cx, cy, OCCUPIED);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    fn square() -> World {
        let text = "name = \"sq\"\nsize = [1.0, 1.0]\nstart = [0.0, 0.0, 0.0]\n\
            [[walls]]\npoints = [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]]\nclosed = true\n\
            [[walls]]\npoints = [[-0.5, -0.2], [0.3, 0.5]]\n\
            [[obstacles]]\ncenter = [0.2, -0.25]\nsize = [0.2, 0.1]\nyaw_deg = 30\n";
        World::from_toml(text, Path::new("sq.toml")).unwrap()
    }

    #[test]
    fn boundary_is_occupied_and_interior_free() {
        let g = square().rasterize(0.05);
        assert_eq!((g.width, g.height), (20, 20));
        assert_eq!(g.origin, Point2::new(-0.5, -0.5));
        for k in 0..20 {
            assert_eq!(g.get(k, 0), OCCUPIED);
            assert_eq!(g.get(k, 19), OCCUPIED);
            assert_eq!(g.get(0, k), OCCUPIED);
            assert_eq!(g.get(19, k), OCCUPIED);
        }
        assert_eq!(g.at(Point2::new(-0.3, 0.3)), FREE);
        assert_eq!(g.at(Point2::new(0.2, -0.25)), OCCUPIED, "obstacle interior");
    }

    #[test]
    fn diagonal_wall_does_not_leak() {
        let g = square().rasterize(0.05);
        // A 4-connected flood fill from one side of the diagonal wall must not reach the other.
        let mut seen = vec![false; g.width * g.height];
        let mut stack = vec![g.cell_of(Point2::new(-0.4, 0.4)).unwrap()];
        while let Some((x, y)) = stack.pop() {
            if seen[y * g.width + x] || g.get(x, y) == OCCUPIED {
                continue;
            }
            seen[y * g.width + x] = true;
            stack.extend([(x + 1, y), (x - 1, y), (x, y + 1), (x, y - 1)]);
        }
        let (x, y) = g.cell_of(Point2::new(0.4, -0.4)).unwrap();
        assert!(
            !seen[y * g.width + x],
            "free space leaked across the diagonal wall"
        );
        let (x, y) = g.cell_of(Point2::new(-0.4, 0.3)).unwrap();
        assert!(seen[y * g.width + x]);
    }

    #[test]
    fn bad_resolution_gives_empty_grid() {
        assert_eq!(square().rasterize(0.0).cells.len(), 0);
        assert_eq!(square().rasterize(f64::NAN).cells.len(), 0);
    }
}
