//! The lidar map: every keyframe's scan drawn at its pose in the graph, as slam_toolbox
//! draws the map it publishes and saves, at the matching grid's resolution. Each beam's
//! cells add the log-odds of a miss and its end cell those of a hit (Probabilistic
//! Robotics 9.2's inverse sensor model), and the cells are written as map_saver writes a
//! trinary map.

use super::LidarSlam;
use crate::geometry::Point2;
use crate::map::evidence::line_cells;
use crate::map::grid::OccupancyGrid;

/// Log-odds of a hit and of a beam passing (p = 0.7 and 0.4, gmapping's and Probabilistic
/// Robotics' usual choices).
const HIT: f32 = 0.847;
const MISS: f32 = -0.405;
/// map_saver's thresholds (Nav2 `occupied_thresh` 0.65, `free_thresh` 0.25) as log-odds.
const OCCUPIED_AT: f32 = 0.619;
const FREE_AT: f32 = -1.099;
/// Cells kept round the drawn area.
const MARGIN_CELLS: f64 = 2.0;
/// The widest map drawn, metres a side: beyond any flat a small robot maps.
const MAX_SIDE: f64 = 200.0;

impl LidarSlam {
    /// The map of every keyframe at its pose in the graph; `None` before the first
    /// keyframe or when the keyframes spread wider than `MAX_SIDE`.
    pub fn occupancy_grid(&self) -> Option<OccupancyGrid> {
        let res = self.config.resolution;
        let beams: Vec<(Point2, Point2, bool)> = self
            .keyframes()
            .flat_map(|(pose, scan)| {
                let from = pose.position();
                scan.ranges.iter().enumerate().filter_map(move |(k, &r)| {
                    let r = f64::from(r);
                    // REP-117: +inf saw nothing within range_max (free that far), -inf
                    // and NaN say nothing.
                    let (reach, hit) = if r >= scan.range_min && r <= scan.range_max {
                        (r, true)
                    } else if r == f64::INFINITY {
                        (scan.range_max, false)
                    } else {
                        return None;
                    };
                    let a = pose.theta + scan.angle_min + k as f64 * scan.angle_increment;
                    let to = Point2::new(from.x + reach * a.cos(), from.y + reach * a.sin());
                    Some((from, to, hit))
                })
            })
            .collect();
        let first = beams.first()?.0;
        let (mut lo, mut hi) = (first, first);
        for &(a, b, _) in &beams {
            for p in [a, b] {
                lo = Point2::new(lo.x.min(p.x), lo.y.min(p.y));
                hi = Point2::new(hi.x.max(p.x), hi.y.max(p.y));
            }
        }
        if hi.x - lo.x > MAX_SIDE || hi.y - lo.y > MAX_SIDE {
            return None;
        }
        let origin = Point2::new(lo.x - MARGIN_CELLS * res, lo.y - MARGIN_CELLS * res);
        let width = ((hi.x - origin.x) / res + MARGIN_CELLS).ceil() as usize;
        let height = ((hi.y - origin.y) / res + MARGIN_CELLS).ceil() as usize;
        let mut odds = vec![0.0f32; width * height];
        let cell = |p: Point2| {
            (
                ((p.x - origin.x) / res).floor() as i64,
                ((p.y - origin.y) / res).floor() as i64,
            )
        };
        for (from, to, hit) in beams {
            let (a, b) = (cell(from), cell(to));
            line_cells(a.0, a.1, b.0, b.1, |x, y| {
                if (x, y) != b && x >= 0 && y >= 0 && (x as usize) < width && (y as usize) < height
                {
                    odds[y as usize * width + x as usize] += MISS;
                }
            });
            if hit && b.0 >= 0 && b.1 >= 0 && (b.0 as usize) < width && (b.1 as usize) < height {
                odds[b.1 as usize * width + b.0 as usize] += HIT - MISS;
            }
        }
        let mut grid = OccupancyGrid::new(width, height, res, origin, -1);
        for (c, &l) in grid.cells.iter_mut().zip(&odds) {
            *c = if l >= OCCUPIED_AT {
                100
            } else if l <= FREE_AT {
                0
            } else {
                -1
            };
        }
        Some(grid)
    }
}

#[cfg(test)]
mod tests {
    use super::super::LidarSlamConfig;
    use super::*;
    use crate::data::LaserScan;
    use crate::geometry::Pose2;

    /// A 360-beam scan from the centre of a square room of side 2.05 m (its walls
    /// mid-cell, away from the grid's cell edges).
    fn square_scan() -> LaserScan {
        let n = 360;
        let inc = std::f64::consts::TAU / n as f64;
        let ranges = (0..n)
            .map(|k| {
                let a = -std::f64::consts::PI + k as f64 * inc;
                (1.025 / a.cos().abs().max(a.sin().abs())) as f32
            })
            .collect();
        LaserScan {
            angle_min: -std::f64::consts::PI,
            angle_increment: inc,
            range_min: 0.12,
            range_max: 3.5,
            ranges,
        }
    }

    #[test]
    fn a_room_seen_from_its_centre_is_walls_round_free_floor() {
        let mut slam = LidarSlam::new(
            &LidarSlamConfig::default(),
            Pose2::default(),
            Pose2::default(),
        );
        let scan = square_scan();
        for _ in 0..3 {
            slam.update(Pose2::default(), &scan);
        }
        let grid = slam.occupancy_grid().unwrap();
        let at = |x: f64, y: f64| {
            let cx = ((x - grid.origin.x) / grid.resolution).floor() as usize;
            let cy = ((y - grid.origin.y) / grid.resolution).floor() as usize;
            grid.cells[cy * grid.width + cx]
        };
        assert_eq!(at(1.025, 0.3), 100, "the east wall");
        assert_eq!(at(-0.3, -1.025), 100, "the south wall");
        assert_eq!(at(0.3, 0.3), 0, "the floor");
        assert_eq!(at(1.1, 1.1), -1, "beyond the corner, unseen");
    }
}
