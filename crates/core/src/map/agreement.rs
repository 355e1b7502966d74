//! Whether a saved map belongs where the robot is: before a loaded map's walls join the
//! planning map, the console holds it against what the robot has already sensed.

use super::grid::OccupancyGrid;
use crate::geometry::Point2;

/// A cell at or above this value is a wall (map_server's default `occupied_thresh`, 0.65).
const OCCUPIED_AT: i8 = 65;
/// A cell at or below this value is free space (map_server's `free_thresh`, 0.196).
const FREE_AT: i8 = 19;
/// Sizes that differ by more than this factor are not the same place.
const SIZE_FACTOR: f64 = 1.5;
/// Walls the two maps must share a sensed area on before they are compared at all.
const WALLS_TO_JUDGE: usize = 20;
/// A wall lies on open floor when the robot saw free space this far all round it,
/// metres: walls drawn thick (a saved map's inflated obstacles) or a few centimetres off
/// still touch something not free within it.
const OPEN_FLOOR: f64 = 0.25;
/// The share of those walls that may fall on open floor (a door opened, a chair
/// moved) before the maps disagree.
const WALLS_ON_FREE: f64 = 0.10;

/// One way a map disagrees with the robot's own, in words for the console.
#[derive(Clone, Debug, PartialEq)]
pub enum Mismatch {
    /// Width and height, metres: the file's, then the robot's map.
    Size((f64, f64), (f64, f64)),
    /// The robot's position lies outside the file's map.
    RobotOutside(Point2),
    /// The robot's position is a wall in the file's map.
    RobotInWall(Point2),
    /// Of the file's walls where the robot has sensed, this many (of so many) lie on open
    /// floor the robot saw free all round.
    WallsOnFree(usize, usize),
}

impl std::fmt::Display for Mismatch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Mismatch::Size(file, own) => write!(
                f,
                "it is {:.1} x {:.1} m, the robot's map {:.1} x {:.1} m",
                file.0, file.1, own.0, own.1
            ),
            Mismatch::RobotOutside(p) => {
                write!(f, "the robot at ({:.2}, {:.2}) is outside it", p.x, p.y)
            }
            Mismatch::RobotInWall(p) => {
                write!(
                    f,
                    "the robot at ({:.2}, {:.2}) would be in a wall",
                    p.x, p.y
                )
            }
            Mismatch::WallsOnFree(on_free, judged) => write!(
                f,
                "{on_free} of its {judged} walls where the robot has sensed lie on open floor"
            ),
        }
    }
}

/// How `file` disagrees with the robot's map `own` and its position `robot`; empty when
/// nothing speaks against loading it.
pub fn mismatches(file: &OccupancyGrid, own: &OccupancyGrid, robot: Point2) -> Vec<Mismatch> {
    let mut found = Vec::new();
    let (fw, fh) = file.extent();
    let (ow, oh) = own.extent();
    let apart = |a: f64, b: f64| a.max(b) > SIZE_FACTOR * a.min(b).max(f64::EPSILON);
    if apart(fw, ow) || apart(fh, oh) {
        found.push(Mismatch::Size((fw, fh), (ow, oh)));
    }
    match file.cell_of(robot) {
        None => found.push(Mismatch::RobotOutside(robot)),
        Some((cx, cy)) if file.get(cx, cy) >= OCCUPIED_AT => {
            found.push(Mismatch::RobotInWall(robot))
        }
        Some(_) => {}
    }
    let open = OpenFloor::of(own);
    let (mut judged, mut on_free) = (0, 0);
    for cy in 0..file.height {
        for cx in 0..file.width {
            if file.get(cx, cy) < OCCUPIED_AT {
                continue;
            }
            let Some((ox, oy)) = own.cell_of(file.center_of(cx, cy)) else {
                continue;
            };
            if own.get(ox, oy) < 0 {
                continue;
            }
            judged += 1;
            if open.at(ox, oy) {
                on_free += 1;
            }
        }
    }
    if judged >= WALLS_TO_JUDGE && on_free as f64 > WALLS_ON_FREE * judged as f64 {
        found.push(Mismatch::WallsOnFree(on_free, judged));
    }
    found
}

/// Which of a grid's cells have only free space within `OPEN_FLOOR` of them, by a box
/// count over a summed-area table of the cells that are not free.
struct OpenFloor {
    width: usize,
    height: usize,
    reach: usize,
    /// `sums[(y + 1) * (width + 1) + x + 1]`: cells not free in [0, x] x [0, y].
    sums: Vec<u32>,
}

impl OpenFloor {
    fn of(grid: &OccupancyGrid) -> Self {
        let (w, h) = (grid.width, grid.height);
        let mut sums = vec![0u32; (w + 1) * (h + 1)];
        for y in 0..h {
            let mut row = 0;
            for x in 0..w {
                let value = grid.get(x, y);
                row += u32::from(!(0..=FREE_AT).contains(&value));
                sums[(y + 1) * (w + 1) + x + 1] = sums[y * (w + 1) + x + 1] + row;
            }
        }
        let reach = (OPEN_FLOOR / grid.resolution).ceil() as usize;
        Self {
            width: w,
            height: h,
            reach,
            sums,
        }
    }

    /// Whether every cell within reach of (x, y) is free (off the grid counts as not).
    fn at(&self, x: usize, y: usize) -> bool {
        let r = self.reach;
        if x < r || y < r || x + r >= self.width || y + r >= self.height {
            return false;
        }
        let w = self.width + 1;
        let (x0, y0, x1, y1) = (x - r, y - r, x + r + 1, y + r + 1);
        let count = self.sums[y1 * w + x1] + self.sums[y0 * w + x0]
            - self.sums[y0 * w + x1]
            - self.sums[y1 * w + x0];
        count == 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::grid::{FREE, OCCUPIED, UNKNOWN};

    /// A square room of `side` metres at 5 cm, walls on its border, free inside.
    fn room(side: f64, origin: Point2) -> OccupancyGrid {
        let n = (side / 0.05).round() as usize;
        let mut g = OccupancyGrid::new(n, n, 0.05, origin, FREE);
        for i in 0..n {
            for (x, y) in [(i, 0), (i, n - 1), (0, i), (n - 1, i)] {
                g.set(x, y, OCCUPIED);
            }
        }
        g
    }

    #[test]
    fn the_same_room_agrees() {
        let own = room(4.0, Point2::new(-2.0, -2.0));
        assert!(mismatches(&own.clone(), &own, Point2::new(0.5, 0.5)).is_empty());
    }

    #[test]
    fn a_room_not_yet_sensed_agrees() {
        let mut own = room(4.0, Point2::new(-2.0, -2.0));
        own.cells.fill(UNKNOWN);
        let file = room(4.0, Point2::new(-2.0, -2.0));
        assert!(mismatches(&file, &own, Point2::new(0.0, 0.0)).is_empty());
    }

    #[test]
    fn a_far_bigger_map_is_named_by_its_size() {
        let own = room(4.0, Point2::new(-2.0, -2.0));
        let file = room(19.2, Point2::new(-9.6, -9.6));
        let found = mismatches(&file, &own, Point2::new(0.5, 0.5));
        assert!(matches!(found[0], Mismatch::Size(..)), "{found:?}");
        assert!(found[0].to_string().contains("19.2 x 19.2 m"));
    }

    #[test]
    fn walls_across_sensed_free_space_disagree() {
        let own = room(4.0, Point2::new(-2.0, -2.0));
        // The same size, shifted by a metre: its walls cross the robot's free floor.
        let file = room(4.0, Point2::new(-1.0, -1.0));
        let found = mismatches(&file, &own, Point2::new(0.5, 0.5));
        assert!(
            found.iter().any(|m| matches!(m, Mismatch::WallsOnFree(..))),
            "{found:?}"
        );
    }

    #[test]
    fn a_robot_off_the_map_or_in_a_wall_disagrees() {
        let own = room(4.0, Point2::new(-2.0, -2.0));
        let file = room(4.0, Point2::new(-2.0, -2.0));
        let outside = mismatches(&file, &own, Point2::new(3.0, 0.0));
        assert_eq!(outside, vec![Mismatch::RobotOutside(Point2::new(3.0, 0.0))]);
        let wall = mismatches(&file, &own, Point2::new(-1.99, 0.0));
        assert_eq!(wall, vec![Mismatch::RobotInWall(Point2::new(-1.99, 0.0))]);
    }
}
