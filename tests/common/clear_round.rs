//! Whether a spot of a generated world is open all round, for goals the tests pick.

use navdeck::geometry::Point2;
use navdeck::map::grid::OccupancyGrid;

/// Whether every point within `r` of `p` (rings 5 cm apart, 16 bearings each) lies inside
/// a `w` x `h` world centred on the origin, 10 cm clear of its edge, on cells of `grid`
/// that are not occupied.
pub fn clear_round(grid: &OccupancyGrid, (w, h): (f64, f64), p: Point2, r: f64) -> bool {
    let mut k = 0.0;
    while k <= r {
        for a in 0..16 {
            let angle = f64::from(a) * std::f64::consts::TAU / 16.0;
            let q = Point2::new(p.x + k * angle.cos(), p.y + k * angle.sin());
            if q.x.abs() > w / 2.0 - 0.1 || q.y.abs() > h / 2.0 - 0.1 || grid.at(q) > 50 {
                return false;
            }
        }
        k += 0.05;
    }
    true
}
