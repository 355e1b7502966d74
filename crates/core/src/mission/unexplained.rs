//! Small things the lidar has mapped that no marker explains. A block is found only by
//! its markers, and a block's markers face only some ways: a camera that passed it on
//! the wrong side saw nothing. The lidar sees it from every side as a small isolated
//! cluster of occupied cells, so such a cluster is worth a look from around it before
//! exploration ends (navdeck's).

use super::clusters::clusters;
use crate::geometry::Point2;
use crate::map::costmap::Costmap;

/// Side of the cells occupied lidar cells are gathered into, metres: lidar hits on one
/// small face lie a beam spacing apart (1.7 cm at 1 m for 360 beams), so they join.
pub const GATHER: f64 = 0.05;

/// A small object stands clear of other structure: other occupied `GATHER` cells within
/// this of its cluster, metres, make it part of something bigger. A wall mapped twice
/// by a drifting pose leaves short copies beside the wall (the 1° beams cross a 1 cm
/// copy only here and there, so misses never clear it whole), and these are not blocks.
const CLEAR_AROUND: f64 = 0.2;
/// Occupied `GATHER` cells of other structure tolerated within `CLEAR_AROUND`: a stray
/// hit or two is noise, three (15 cm) is a wall or a box.
const OTHERS_TOLERATED: usize = 2;

/// Centres of the clusters of `occupied` cells (row-major over `map`) that fit in a
/// square of side `max_size` and stand clear of other structure (`CLEAR_AROUND`), cells
/// joined when they share or touch a `GATHER` cell.
pub fn small_objects(map: &Costmap, occupied: &[bool], max_size: f64) -> Vec<Point2> {
    if occupied.len() != map.width * map.height || max_size <= 0.0 {
        return Vec::new();
    }
    let k = (GATHER / map.resolution).round().max(1.0) as usize;
    let (w, h) = (map.width.div_ceil(k), map.height.div_ceil(k));
    let mut hits = vec![0u32; w * h];
    let mut sums = vec![(0.0, 0.0); w * h];
    for (i, _) in occupied.iter().enumerate().filter(|(_, o)| **o) {
        let (cx, cy) = (i % map.width, i / map.width);
        let j = (cy / k) * w + cx / k;
        hits[j] += 1;
        let c = map.center_of(cx, cy);
        sums[j].0 += c.x;
        sums[j].1 += c.y;
    }
    let cell = k as f64 * map.resolution;
    let ring = (CLEAR_AROUND / cell).ceil() as usize;
    clusters(w, h, |x, y| hits[y * w + x] > 0)
        .into_iter()
        .filter(|cluster| {
            let (x0, x1, y0, y1) = bounds(cluster);
            // Two clusters' extremes are whole cells apart; the object is at most this big.
            let span = |lo: usize, hi: usize| (hi - lo) as f64 * cell;
            if span(x0, x1) >= max_size || span(y0, y1) >= max_size {
                return false;
            }
            let near = (y0.saturating_sub(ring)..=(y1 + ring).min(h - 1))
                .flat_map(|y| {
                    (x0.saturating_sub(ring)..=(x1 + ring).min(w - 1)).map(move |x| (x, y))
                })
                .filter(|&(x, y)| hits[y * w + x] > 0)
                .count();
            near - cluster.len() <= OTHERS_TOLERATED
        })
        .map(|cluster| {
            let (n, sx, sy) = cluster
                .iter()
                .fold((0u32, 0.0, 0.0), |(n, sx, sy), &(x, y)| {
                    let j = y * w + x;
                    (n + hits[j], sx + sums[j].0, sy + sums[j].1)
                });
            Point2::new(sx / f64::from(n), sy / f64::from(n))
        })
        .collect()
}

/// A cluster's cells' least and greatest column and row: (x0, x1, y0, y1).
fn bounds(cluster: &[(usize, usize)]) -> (usize, usize, usize, usize) {
    cluster.iter().fold(
        (usize::MAX, 0, usize::MAX, 0),
        |(x0, x1, y0, y1), &(x, y)| (x0.min(x), x1.max(x), y0.min(y), y1.max(y)),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::costmap::FREE;

    /// 2 m x 2 m at 1 cm, with `cells` occupied.
    fn grid(cells: &[(usize, usize)]) -> (Costmap, Vec<bool>) {
        let map = Costmap::new(200, 200, 0.01, Point2::new(0.0, 0.0), FREE);
        let mut occupied = vec![false; 200 * 200];
        for &(x, y) in cells {
            occupied[y * 200 + x] = true;
        }
        (map, occupied)
    }

    #[test]
    fn a_block_face_of_scattered_hits_is_one_small_object_at_its_centre() {
        // A 5 cm face at x = 1.0 m, hit every 2 cm.
        let (map, occupied) = grid(&[(100, 100), (100, 102), (100, 104)]);
        let found = small_objects(&map, &occupied, 0.15);
        assert_eq!(found.len(), 1, "{found:?}");
        assert!(
            found[0].distance(Point2::new(1.005, 1.025)) < 0.01,
            "{found:?}"
        );
    }

    #[test]
    fn a_wall_and_a_box_are_too_big_and_two_blocks_apart_are_two() {
        let mut cells: Vec<(usize, usize)> = (0..200).map(|y| (5, y)).collect();
        cells.extend((60..95).map(|x| (x, 40)));
        cells.extend([(150, 150), (151, 150), (100, 10)]);
        let (map, occupied) = grid(&cells);
        let mut found = small_objects(&map, &occupied, 0.15);
        found.sort_by(|a, b| a.x.total_cmp(&b.x));
        assert_eq!(found.len(), 2, "{found:?}");
        assert!(found[0].distance(Point2::new(1.005, 0.105)) < 0.01);
        assert!(found[1].distance(Point2::new(1.51, 1.505)) < 0.01);
        assert!(
            small_objects(&map, &occupied, 0.0).is_empty(),
            "0 turns it off"
        );
        assert!(
            small_objects(&map, &[], 0.15).is_empty(),
            "no lidar, nothing"
        );
    }

    #[test]
    fn a_short_copy_of_a_wall_beside_it_is_not_an_object() {
        // A wall along y = 1.0 m, and 8 cm of it mapped again 10 cm off (a drifted pose).
        let mut cells: Vec<(usize, usize)> = (0..200).map(|x| (x, 100)).collect();
        cells.extend((60..68).map(|x| (x, 90)));
        // And a block 30 cm from the wall, which is one.
        cells.extend([(150, 70), (151, 70)]);
        let (map, occupied) = grid(&cells);
        let found = small_objects(&map, &occupied, 0.15);
        assert_eq!(found.len(), 1, "{found:?}");
        assert!(
            found[0].distance(Point2::new(1.51, 0.705)) < 0.01,
            "{found:?}"
        );
    }
}
