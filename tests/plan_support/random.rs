//! Small random grids, and cells on them, for checking searches against each other.

use navdeck::geometry::Point2;
use navdeck::map::costmap::{Costmap, LETHAL};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// A cell anywhere on `map`.
pub fn random_cell(rng: &mut ChaCha8Rng, map: &Costmap) -> (usize, usize) {
    (
        rng.random_range(0..map.width),
        rng.random_range(0..map.height),
    )
}

/// A small random grid: some lethal cells, some unknown, costs scattered over 0..=99.
pub fn random_grid(rng: &mut ChaCha8Rng) -> Costmap {
    let (w, h) = (rng.random_range(2..16), rng.random_range(2..16));
    let mut map = Costmap::new(w, h, 0.1, Point2::new(-0.5, 0.25), 0);
    for c in map.cost.iter_mut() {
        let r: f64 = rng.random();
        *c = if r < 0.25 {
            LETHAL + rng.random_range(0..3) * 50 // 100, 150 or 200: all lethal
        } else if r < 0.3 {
            255
        } else if r < 0.6 {
            rng.random_range(0..100)
        } else {
            0
        };
    }
    map
}
