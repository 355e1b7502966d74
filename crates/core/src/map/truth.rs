//! How a map agrees with the world's true walls, for scoring a map a robot built: the
//! share of true wall cells the map has as occupied (recall) and the share of the map's
//! occupied cells that are true walls (precision), each within one cell.

use super::grid::OccupancyGrid;
use crate::geometry::{Point2, Segment};
use serde::Serialize;

/// A cell at or above this value is a wall (map_server's default `occupied_thresh`, 0.65).
pub const OCCUPIED_AT: i8 = 65;
/// Points along a wall are taken this often, in cells: four to a cell, so a wall crossing
/// a cell by more than a quarter of its side marks it.
const SAMPLES_PER_CELL: f64 = 4.0;
/// A wall point this far past the grid's edge, in cells, is on its last cell: a boundary
/// wall lies exactly on the edge of a map that covers the world.
const EDGE: f64 = 1e-6;

/// A map held against the true walls, each within one cell (8-neighbourhood).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct WallAgreement {
    /// `wall_cells_mapped / wall_cells`; 0 when no wall lies on the grid.
    pub wall_recall: f64,
    /// `occupied_on_walls / occupied_cells`; 0 when nothing is mapped as occupied.
    pub wall_precision: f64,
    /// Cells a true wall passes through, within the grid.
    pub wall_cells: usize,
    /// Of those, the ones with a mapped occupied cell within one cell.
    pub wall_cells_mapped: usize,
    /// Cells the map holds as occupied.
    pub occupied_cells: usize,
    /// Of those, the ones within one cell of a true wall cell.
    pub occupied_on_walls: usize,
}

/// How `map` agrees with the true `walls` (segments, box outlines among them), at the
/// map's resolution and within its extent.
pub fn wall_agreement(map: &OccupancyGrid, walls: &[Segment]) -> WallAgreement {
    let truth = wall_cells(map, walls);
    let occupied: Vec<bool> = map.cells.iter().map(|&v| v >= OCCUPIED_AT).collect();
    let count = |mask: &[bool]| mask.iter().filter(|&&m| m).count();
    let near = |mask: &[bool], other: &[bool]| {
        (0..mask.len())
            .filter(|&k| mask[k] && any_within_one(map, other, k))
            .count()
    };
    let (wall_cells, occupied_cells) = (count(&truth), count(&occupied));
    let wall_cells_mapped = near(&truth, &occupied);
    let occupied_on_walls = near(&occupied, &truth);
    let share = |part: usize, whole: usize| {
        if whole == 0 {
            0.0
        } else {
            part as f64 / whole as f64
        }
    };
    WallAgreement {
        wall_recall: share(wall_cells_mapped, wall_cells),
        wall_precision: share(occupied_on_walls, occupied_cells),
        wall_cells,
        wall_cells_mapped,
        occupied_cells,
        occupied_on_walls,
    }
}

/// The cells the walls pass through, as a mask over `map`'s cells: points taken along each
/// wall `SAMPLES_PER_CELL` to a cell, those on the grid (or on its very edge) marked.
fn wall_cells(map: &OccupancyGrid, walls: &[Segment]) -> Vec<bool> {
    let mut mask = vec![false; map.width * map.height];
    let res = map.resolution;
    if !(res.is_finite() && res > 0.0) {
        return mask;
    }
    let on_grid = |v: f64, count: usize| {
        let f = (v / res).floor();
        let inside = v / res >= -EDGE && v / res <= count as f64 + EDGE;
        inside.then(|| (f.max(0.0) as usize).min(count.saturating_sub(1)))
    };
    for s in walls {
        let steps = (s.length() / res * SAMPLES_PER_CELL).ceil().max(1.0) as usize;
        for i in 0..=steps {
            let t = i as f64 / steps as f64;
            let p = Point2::new(s.a.x + t * (s.b.x - s.a.x), s.a.y + t * (s.b.y - s.a.y));
            let cell = (
                on_grid(p.x - map.origin.x, map.width),
                on_grid(p.y - map.origin.y, map.height),
            );
            if let (Some(cx), Some(cy)) = cell {
                mask[cy * map.width + cx] = true;
            }
        }
    }
    mask
}

/// Whether `mask` holds any cell within one cell (the 3 x 3 block) of cell `k`.
fn any_within_one(map: &OccupancyGrid, mask: &[bool], k: usize) -> bool {
    let (x, y) = ((k % map.width) as i64, (k / map.width) as i64);
    (-1..=1).any(|dy| {
        (-1..=1).any(|dx| {
            let (nx, ny) = (x + dx, y + dy);
            let on = (0..map.width as i64).contains(&nx) && (0..map.height as i64).contains(&ny);
            on && mask[ny as usize * map.width + nx as usize]
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::grid::{FREE, OCCUPIED, UNKNOWN};

    /// A 2 m x 2 m grid of 0.1 m cells from (0, 0), and a wall along y = 1.05 from
    /// x = 0.25 to 1.75: the cells of row 10, columns 2 to 17 (16 cells).
    fn setting() -> (OccupancyGrid, Vec<Segment>) {
        let grid = OccupancyGrid::new(20, 20, 0.1, Point2::new(0.0, 0.0), FREE);
        let wall = Segment::new(Point2::new(0.25, 1.05), Point2::new(1.75, 1.05));
        (grid, vec![wall])
    }

    fn mapped_row(row: usize) -> OccupancyGrid {
        let (mut grid, _) = setting();
        for x in 2..=17 {
            grid.set(x, row, OCCUPIED);
        }
        grid
    }

    #[test]
    fn a_perfect_map_agrees_fully() {
        let (_, walls) = setting();
        let a = wall_agreement(&mapped_row(10), &walls);
        assert_eq!((a.wall_cells, a.wall_cells_mapped), (16, 16));
        assert_eq!((a.occupied_cells, a.occupied_on_walls), (16, 16));
        assert_eq!((a.wall_recall, a.wall_precision), (1.0, 1.0));
        // One cell off is still within one cell.
        let a = wall_agreement(&mapped_row(11), &walls);
        assert_eq!((a.wall_recall, a.wall_precision), (1.0, 1.0));
    }

    #[test]
    fn a_map_shifted_by_three_cells_misses_the_wall() {
        let (_, walls) = setting();
        let a = wall_agreement(&mapped_row(13), &walls);
        assert_eq!((a.wall_recall, a.wall_precision), (0.0, 0.0));
        // Shifted three cells along the wall instead: the three cells at each end miss.
        let (mut along, _) = setting();
        for x in 5..=19 {
            along.set(x, 10, OCCUPIED);
        }
        let a = wall_agreement(&along, &walls);
        // True cells 2..=17 matched from 4 on: 14 of 16; mapped 5..=19 on a wall up to 18:
        // 14 of 15.
        assert_eq!((a.wall_cells_mapped, a.occupied_on_walls), (14, 14));
        assert_eq!(a.wall_recall, 14.0 / 16.0);
        assert_eq!(a.wall_precision, 14.0 / 15.0);
    }

    #[test]
    fn an_empty_map_recalls_nothing_and_clutter_lowers_precision() {
        let (mut grid, walls) = setting();
        let a = wall_agreement(&grid, &walls);
        assert_eq!(
            (a.wall_recall, a.wall_cells, a.occupied_cells),
            (0.0, 16, 0)
        );
        grid.cells.fill(UNKNOWN);
        assert_eq!(wall_agreement(&grid, &walls).wall_recall, 0.0);
        // The wall and four cells of clutter; one cell below the threshold counts for nothing.
        let mut cluttered = mapped_row(10);
        for x in [0, 5, 10, 15] {
            cluttered.set(x, 18, OCCUPIED);
        }
        cluttered.set(3, 3, OCCUPIED_AT - 1);
        let a = wall_agreement(&cluttered, &walls);
        assert_eq!((a.wall_recall, a.occupied_cells), (1.0, 20));
        assert_eq!(a.wall_precision, 16.0 / 20.0);
    }

    #[test]
    fn walls_count_only_within_the_grid_and_the_far_edge_is_on_it() {
        let (grid, _) = setting();
        // From x = 1.55 to 3.0: columns 15 to 19 lie on the grid.
        let past = Segment::new(Point2::new(1.55, 0.55), Point2::new(3.0, 0.55));
        assert_eq!(wall_agreement(&grid, &[past]).wall_cells, 5);
        // Along the top edge, y = 2.0: the last row, columns 2 to 17.
        let edge = Segment::new(Point2::new(0.25, 2.0), Point2::new(1.75, 2.0));
        let mut top = grid.clone();
        for x in 2..=17 {
            top.set(x, 19, OCCUPIED);
        }
        let a = wall_agreement(&top, &[edge]);
        assert_eq!(
            (a.wall_cells, a.wall_recall, a.wall_precision),
            (16, 1.0, 1.0)
        );
        // Wholly outside: nothing.
        let away = Segment::new(Point2::new(3.0, 3.0), Point2::new(4.0, 3.0));
        assert_eq!(wall_agreement(&grid, &[away]).wall_cells, 0);
    }
}
