//! Obstacle points in the robot's frame, from what a robot has: a lidar's scan, or for a
//! robot without one, the occupied cells of a map around its estimated pose.

use crate::data::LaserScan;
use crate::geometry::{Point2, Pose2};
use crate::map::grid::OccupancyGrid;
use crate::map::truth::OCCUPIED_AT;

/// Where an obstacle reading came from, named when the data is missing or too old.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SourceKind {
    /// A lidar's scan (`points_from_scan`).
    #[default]
    Scan,
    /// The map's occupied cells around the estimated pose (`points_from_grid`).
    Map,
}

impl SourceKind {
    /// What a message says is missing: "no scan for 0.6 s".
    pub fn missing(self) -> &'static str {
        match self {
            SourceKind::Scan => "scan",
            SourceKind::Map => "pose on the map",
        }
    }
}

/// The obstacle points one check weighs, and how old they are.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Obstacles<'a> {
    /// Points in the robot's frame (x forward, y left, metres).
    pub points: &'a [Point2],
    /// Seconds since the data was taken; `None` when there never was any.
    pub age: Option<f64>,
    pub source: SourceKind,
}

/// The scan's hits in the robot's frame, for a lidar mounted at `lidar` in that frame
/// (`Pose2::default()` for one on the robot's centre). Beams with no return are dropped.
pub fn points_from_scan(scan: &LaserScan, lidar: Pose2) -> Vec<Point2> {
    scan.hits(lidar).collect()
}

/// Points are laid across an occupied cell at most this far apart, metres: a wall in a
/// 5 cm map reads as densely as a lidar sees it close by, so `min_points` means about
/// the same for either source.
pub const CELL_SAMPLE_SPACING: f64 = 0.025;

/// The occupied cells of `grid` (at or above map_server's `occupied_thresh`, 0.65) within
/// `radius` of the robot at `pose` (map frame), as points in the robot's frame: each cell
/// a small lattice of points spanning its whole square, edges included, so the points
/// nearest the robot lie on the cell's edge rather than its centre.
pub fn points_from_grid(grid: &OccupancyGrid, pose: Pose2, radius: f64) -> Vec<Point2> {
    let mut points = Vec::new();
    let at = pose.position();
    let columns = grid.columns_in(at.x - radius, at.x + radius);
    let rows = grid.rows_in(at.y - radius, at.y + radius);
    let (Some((x0, x1)), Some((y0, y1))) = (columns, rows) else {
        return points;
    };
    let res = grid.resolution;
    // Samples per side: both edges and enough between them.
    let per_side = (res / CELL_SAMPLE_SPACING).ceil().max(1.0) as usize + 1;
    let step = res / (per_side - 1) as f64;
    for cy in y0..=y1 {
        for cx in x0..=x1 {
            if grid.get(cx, cy) < OCCUPIED_AT {
                continue;
            }
            let corner = Point2::new(
                grid.origin.x + cx as f64 * res,
                grid.origin.y + cy as f64 * res,
            );
            for j in 0..per_side {
                for i in 0..per_side {
                    let p = Point2::new(corner.x + i as f64 * step, corner.y + j as f64 * step);
                    if p.distance(at) <= radius {
                        points.push(pose.inverse_transform_point(p));
                    }
                }
            }
        }
    }
    points
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::grid::{FREE, OCCUPIED};

    #[test]
    fn a_scan_beam_straight_ahead_lands_ahead_and_misses_are_dropped() {
        let scan = LaserScan {
            angle_min: 0.0,
            angle_increment: std::f64::consts::FRAC_PI_2,
            range_min: 0.12,
            range_max: 3.5,
            ranges: vec![0.5, f32::INFINITY, 0.05, 1.0],
        };
        let points = points_from_scan(&scan, Pose2::default());
        // Beam 0 ahead; beam 1 no return; beam 2 under range_min; beam 3 to the right.
        assert_eq!(points.len(), 2);
        assert!((points[0].x - 0.5).abs() < 1e-6 && points[0].y.abs() < 1e-6);
        assert!(points[1].x.abs() < 1e-6 && (points[1].y + 1.0).abs() < 1e-6);
    }

    #[test]
    fn a_wall_cell_ahead_of_a_turned_robot_is_ahead_in_its_frame() {
        // A 1 m map of 5 cm cells, one occupied cell spanning x 0.50..0.55, y 0.80..0.85.
        let mut grid = OccupancyGrid::new(20, 20, 0.05, Point2::new(0.0, 0.0), FREE);
        grid.set(10, 16, OCCUPIED);
        // The robot at (0.525, 0.5) facing +y: the cell lies 0.30..0.35 m ahead.
        let pose = Pose2::new(0.525, 0.5, std::f64::consts::FRAC_PI_2);
        let points = points_from_grid(&grid, pose, 0.5);
        assert!(!points.is_empty());
        let nearest = points.iter().map(|p| p.x).fold(f64::INFINITY, f64::min);
        let farthest = points.iter().map(|p| p.x).fold(f64::NEG_INFINITY, f64::max);
        assert!((nearest - 0.30).abs() < 1e-9, "{nearest}");
        assert!((farthest - 0.35).abs() < 1e-9, "{farthest}");
        assert!(points.iter().all(|p| p.y.abs() <= 0.025 + 1e-9));
        // Out of reach, nothing.
        assert!(points_from_grid(&grid, pose, 0.25).is_empty());
    }
}
