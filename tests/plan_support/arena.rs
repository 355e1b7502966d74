//! The A* benchmark's arena: a 4 m square at 1 cm with walls, boxes and cost gradients.

use navdeck::geometry::Point2;
use navdeck::map::costmap::{Costmap, INFLATED, LETHAL};

/// Obstacles of the benchmark arena, in cells: (x0, y0, x1, y1) inclusive.
const BLOCKS: [(usize, usize, usize, usize); 6] = [
    (100, 0, 105, 300),
    (200, 100, 205, 399),
    (300, 0, 305, 280),
    (140, 320, 170, 350),
    (240, 40, 270, 70),
    (330, 330, 370, 360),
];

/// A 4 m square at 1 cm: three long walls and three boxes, each with a 5-cell inflated ring
/// (cost 70) and a gradient falling from 69 to 0 over the next 15 cells. Deterministic.
pub fn arena() -> Costmap {
    let mut map = Costmap::new(400, 400, 0.01, Point2::new(0.0, 0.0), 0);
    for y in 0..400 {
        for x in 0..400 {
            let d = BLOCKS
                .iter()
                .map(|&(x0, y0, x1, y1)| {
                    let dx = x0.saturating_sub(x).max(x.saturating_sub(x1)) as f64;
                    let dy = y0.saturating_sub(y).max(y.saturating_sub(y1)) as f64;
                    dx.hypot(dy)
                })
                .fold(f64::INFINITY, f64::min);
            let cost = if d == 0.0 {
                LETHAL
            } else if d <= 5.0 {
                INFLATED
            } else if d < 20.0 {
                (69.0 * (20.0 - d) / 15.0) as u8
            } else {
                0
            };
            map.set(x, y, cost);
        }
    }
    map
}
