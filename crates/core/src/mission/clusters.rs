//! Grouping grid cells into 8-connected clusters, and the cell that stands for each: the
//! frontiers of unknown space and the free space the camera has not looked at are both
//! found this way.

use std::collections::VecDeque;

/// The 8-connected clusters of the cells of a `w` x `h` grid for which `member` holds, in
/// row-major order of their first cell, each listing its cells breadth-first.
pub fn clusters(
    w: usize,
    h: usize,
    member: impl Fn(usize, usize) -> bool,
) -> Vec<Vec<(usize, usize)>> {
    let mut done = vec![false; w * h];
    let mut out = Vec::new();
    for y in 0..h {
        for x in 0..w {
            if done[y * w + x] || !member(x, y) {
                continue;
            }
            done[y * w + x] = true;
            let mut cluster = vec![(x, y)];
            let mut queue = VecDeque::from([(x, y)]);
            while let Some((cx, cy)) = queue.pop_front() {
                for (nx, ny) in neighbours(cx, cy, w, h) {
                    if !done[ny * w + nx] && member(nx, ny) {
                        done[ny * w + nx] = true;
                        cluster.push((nx, ny));
                        queue.push_back((nx, ny));
                    }
                }
            }
            out.push(cluster);
        }
    }
    out
}

/// Of the cells `allowed`, the one nearest the centroid of the whole cluster (the first
/// of equals in the cluster's order); `None` when none is allowed.
pub fn nearest_centroid(
    cluster: &[(usize, usize)],
    allowed: impl Fn(&(usize, usize)) -> bool,
) -> Option<(usize, usize)> {
    let n = cluster.len() as f64;
    let (sx, sy) =
        (cluster.iter()).fold((0.0, 0.0), |(a, b), &(x, y)| (a + x as f64, b + y as f64));
    let (mx, my) = (sx / n, sy / n);
    let off = |c: &(usize, usize)| (c.0 as f64 - mx).hypot(c.1 as f64 - my);
    (cluster.iter().copied())
        .filter(|c| allowed(c))
        .min_by(|a, b| off(a).total_cmp(&off(b)))
}

fn neighbours(x: usize, y: usize, w: usize, h: usize) -> impl Iterator<Item = (usize, usize)> {
    (-1i64..=1)
        .flat_map(|dy| (-1i64..=1).map(move |dx| (dx, dy)))
        .filter(|&d| d != (0, 0))
        .map(move |(dx, dy)| (x as i64 + dx, y as i64 + dy))
        .filter(move |&(a, b)| a >= 0 && b >= 0 && a < w as i64 && b < h as i64)
        .map(|(a, b)| (a as usize, b as usize))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn diagonal_neighbours_join_and_the_centre_cell_stands_for_the_cluster() {
        // Two clusters in a 6 x 3 grid: a diagonal run of three, and one lone cell.
        let member = |x: usize, y: usize| matches!((x, y), (0, 0) | (1, 1) | (2, 2) | (5, 0));
        let found = clusters(6, 3, member);
        assert_eq!(found, vec![vec![(0, 0), (1, 1), (2, 2)], vec![(5, 0)]]);
        assert_eq!(nearest_centroid(&found[0], |_| true), Some((1, 1)));
        assert_eq!(nearest_centroid(&found[0], |c| *c != (1, 1)), Some((0, 0)));
        assert_eq!(nearest_centroid(&found[1], |_| false), None);
    }
}
