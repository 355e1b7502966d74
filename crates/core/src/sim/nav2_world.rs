//! A twin world made from a Nav2 map (map_server YAML + PGM): its occupied cells become
//! walls, at the map's resolution, for the lidar to see and the robot to collide with,
//! and the map's edge is a wall too. The map frame is kept: the world is the smallest
//! square-cornered extent centred on the origin that holds the whole map.
//!
//! Walls are the cell edges between an occupied cell and any other, joined along a row
//! or column into one segment per straight run, so that a wall of a hundred cells is one
//! segment for the lidar, not a hundred.

use super::{World, WorldError};
use crate::geometry::{Point2, Pose2, Segment};
use crate::map::grid::{OCCUPIED, OccupancyGrid};
use std::path::Path;

/// A cell at least this occupied is solid (map_server's trinary maps give 0 or 100).
const SOLID: i8 = OCCUPIED / 2;

/// The world of the Nav2 map at `path`, the robot starting at `start` or, without one,
/// at the known-free cell farthest from anything else.
pub fn load(path: &Path, start: Option<Pose2>) -> Result<World, WorldError> {
    // The map's reason alone: the world error names the file already.
    let map = crate::map::io::load(path).map_err(|e| WorldError::Parse {
        path: path.to_path_buf(),
        message: e.reason(),
    })?;
    from_grid(&map.grid, start, path)
}

/// The world of `grid` (named `path` in errors).
pub fn from_grid(
    grid: &OccupancyGrid,
    start: Option<Pose2>,
    path: &Path,
) -> Result<World, WorldError> {
    let invalid = |field: &str, value: String, reason: String| WorldError::Invalid {
        path: path.to_path_buf(),
        line: None,
        field: field.to_string(),
        value,
        reason,
    };
    let (w, h) = grid.extent();
    let (x0, y0) = (grid.origin.x, grid.origin.y);
    // Centred on the map frame's origin, as every world is.
    let width = 2.0 * x0.abs().max((x0 + w).abs());
    let height = 2.0 * y0.abs().max((y0 + h).abs());
    let max = super::checks::MAX_WORLD_SIDE;
    if width > max || height > max {
        return Err(invalid(
            "size",
            format!("[{width:.1}, {height:.1}]"),
            format!("the map with its origin must fit a world of at most {max} m a side"),
        ));
    }
    let start = match start {
        Some(pose) => {
            let at = grid.at(pose.position());
            if grid.cell_of(pose.position()).is_none() || at != 0 {
                return Err(invalid(
                    "start",
                    format!("[{:.2}, {:.2}]", pose.x, pose.y),
                    "must be on a known free cell of the map".into(),
                ));
            }
            pose
        }
        None => roomiest(grid).ok_or_else(|| {
            invalid(
                "image",
                path.display().to_string(),
                "the map has no known free cell to start on".into(),
            )
        })?,
    };
    let name = path
        .file_stem()
        .map_or("nav2 map".to_string(), |s| s.to_string_lossy().into_owned());
    let name: String = name.chars().filter(|c| !c.is_control()).take(80).collect();
    Ok(World {
        name,
        width,
        height,
        start,
        walls: walls(grid),
        markers: Vec::new(),
        blocks: Vec::new(),
        gates: Vec::new(),
        obstacles: Vec::new(),
        track: None,
    })
}

/// The edges between solid cells and the rest, joined into straight runs, and the
/// map's outline.
pub fn walls(grid: &OccupancyGrid) -> Vec<Segment> {
    let (cols, rows, res) = (grid.width, grid.height, grid.resolution);
    let solid = |c: isize, r: isize| {
        c >= 0
            && r >= 0
            && (c as usize) < cols
            && (r as usize) < rows
            && grid.get(c as usize, r as usize) >= SOLID
    };
    let at = |c: usize, r: usize| {
        Point2::new(
            grid.origin.x + c as f64 * res,
            grid.origin.y + r as f64 * res,
        )
    };
    let mut out = Vec::new();
    // Horizontal edges: below row r (between rows r - 1 and r), cells c0..c.
    for r in 0..=rows {
        let mut run: Option<usize> = None;
        for c in 0..=cols {
            let edge =
                c < cols && solid(c as isize, r as isize - 1) != solid(c as isize, r as isize);
            match (run, edge) {
                (None, true) => run = Some(c),
                (Some(c0), false) => {
                    out.push(Segment::new(at(c0, r), at(c, r)));
                    run = None;
                }
                _ => {}
            }
        }
    }
    // Vertical edges: left of column c, rows r0..r.
    for c in 0..=cols {
        let mut run: Option<usize> = None;
        for r in 0..=rows {
            let edge =
                r < rows && solid(c as isize - 1, r as isize) != solid(c as isize, r as isize);
            match (run, edge) {
                (None, true) => run = Some(r),
                (Some(r0), false) => {
                    out.push(Segment::new(at(c, r0), at(c, r)));
                    run = None;
                }
                _ => {}
            }
        }
    }
    // The map's edge: nothing leaves the map.
    let corners = [at(0, 0), at(cols, 0), at(cols, rows), at(0, rows)];
    for k in 0..4 {
        out.push(Segment::new(corners[k], corners[(k + 1) % 4]));
    }
    out
}

/// The centre of the known-free cell farthest (in cells, chessboard distance) from any
/// cell that is not known free: the roomiest place to put a robot down, facing east.
fn roomiest(grid: &OccupancyGrid) -> Option<Pose2> {
    let (cols, rows) = (grid.width, grid.height);
    // Two-pass chessboard distance transform (Rosenfeld & Pfaltz, 1966).
    let mut d = vec![0u32; cols * rows];
    for r in 0..rows {
        for c in 0..cols {
            if grid.get(c, r) != 0 {
                continue;
            }
            let mut v = u32::MAX;
            for (dc, dr) in [(-1, 0), (-1, -1), (0, -1), (1, -1)] {
                let (cc, rr) = (c as isize + dc, r as isize + dr);
                v = v.min(if cc < 0 || rr < 0 || cc as usize >= cols {
                    0
                } else {
                    d[rr as usize * cols + cc as usize]
                });
            }
            d[r * cols + c] = v.saturating_add(1);
        }
    }
    for r in (0..rows).rev() {
        for c in (0..cols).rev() {
            if grid.get(c, r) != 0 {
                continue;
            }
            let mut v = d[r * cols + c];
            for (dc, dr) in [(1, 0), (1, 1), (0, 1), (-1, 1)] {
                let (cc, rr) = (c as isize + dc, r as isize + dr);
                let n = if cc < 0 || cc as usize >= cols || rr as usize >= rows {
                    0
                } else {
                    d[rr as usize * cols + cc as usize]
                };
                v = v.min(n.saturating_add(1));
            }
            d[r * cols + c] = v;
        }
    }
    let best = (0..cols * rows)
        .filter(|&i| d[i] > 0)
        .max_by_key(|&i| (d[i], usize::MAX - i))?;
    let p = grid.center_of(best % cols, best / cols);
    Some(Pose2::new(p.x, p.y, 0.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::grid::{FREE, UNKNOWN};

    /// A 10 x 8 room at 0.1 m: a wall all round, a 2 x 2 pillar, the origin at (-0.5, -0.4).
    fn room() -> OccupancyGrid {
        let mut g = OccupancyGrid::new(10, 8, 0.1, Point2::new(-0.5, -0.4), FREE);
        for c in 0..10 {
            g.set(c, 0, OCCUPIED);
            g.set(c, 7, OCCUPIED);
        }
        for r in 0..8 {
            g.set(0, r, OCCUPIED);
            g.set(9, r, OCCUPIED);
        }
        for (c, r) in [(6, 3), (7, 3), (6, 4), (7, 4)] {
            g.set(c, r, OCCUPIED);
        }
        g
    }

    #[test]
    fn walls_are_the_cell_edges_of_the_solid_cells_joined_into_runs() {
        let walls = walls(&room());
        // The room's outer outline (4), its inner outline (4), the pillar (4), the map
        // edge (4): a straight run is one segment however many cells it spans.
        assert_eq!(walls.len(), 16, "{walls:?}");
        let length: f64 = walls.iter().map(|s| s.a.distance(s.b)).sum();
        // Outer outline 3.6 m, inner 2 (0.8 + 0.6), pillar 0.8, map edge 3.6.
        let expected = 3.6 + 2.0 * (0.8 + 0.6) + 0.8 + 3.6;
        assert!((length - expected).abs() < 1e-9, "{length} vs {expected}");
    }

    #[test]
    fn the_world_keeps_the_map_frame_and_starts_in_the_roomiest_free_cell() {
        let world = from_grid(&room(), None, Path::new("room.yaml")).unwrap();
        // The map spans x -0.5..0.5, y -0.4..0.4: centred already.
        assert!((world.width - 1.0).abs() < 1e-9 && (world.height - 0.8).abs() < 1e-9);
        let s = world.start.position();
        let g = room();
        assert_eq!(g.at(s), FREE, "starts on a free cell");
        // Not next to the walls: two cells in from the outer wall at least.
        assert!(s.x.abs() <= 0.2 + 1e-9 && s.y.abs() <= 0.1 + 1e-9, "{s:?}");
    }

    #[test]
    fn a_start_on_a_wall_or_a_map_without_free_space_is_refused() {
        let on_wall = Pose2::new(-0.45, 0.0, 0.0);
        let e = from_grid(&room(), Some(on_wall), Path::new("room.yaml")).unwrap_err();
        assert!(e.to_string().contains("start"), "{e}");
        let blank = OccupancyGrid::new(4, 4, 0.1, Point2::new(0.0, 0.0), UNKNOWN);
        let e = from_grid(&blank, None, Path::new("blank.yaml")).unwrap_err();
        assert!(e.to_string().contains("no known free cell"), "{e}");
    }
}
