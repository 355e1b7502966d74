//! Collinear removal (seed 001 "Path Simplification": keep only the points where the
//! direction changes).

/// Indices of the cells of an 8-connected path worth keeping: both ends, and every cell where
/// the step direction changes. Repeated cells are dropped.
pub fn simplify(cells: &[(usize, usize)]) -> Vec<usize> {
    let n = cells.len();
    if n <= 2 {
        return (0..n).collect();
    }
    let step =
        |a: (usize, usize), b: (usize, usize)| (b.0 as i64 - a.0 as i64, b.1 as i64 - a.1 as i64);
    let mut keep = vec![0];
    for i in 1..n - 1 {
        let (before, after) = (step(cells[i - 1], cells[i]), step(cells[i], cells[i + 1]));
        if before == (0, 0) {
            continue;
        }
        // Seed 001: the direction changes where the cross product of the two steps is non-zero
        // or they point opposite ways.
        let cross = before.0 * after.1 - before.1 * after.0;
        let dot = before.0 * after.0 + before.1 * after.1;
        if cross != 0 || dot <= 0 {
            keep.push(i);
        }
    }
    keep.push(n - 1);
    keep
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_l_shaped_path_keeps_its_corner_only() {
        let cells: Vec<_> = (0..5)
            .map(|x| (x, 0))
            .chain((1..4).map(|y| (4, y)))
            .collect();
        assert_eq!(simplify(&cells), vec![0, 4, 7]);
    }

    #[test]
    fn short_paths_are_kept_whole() {
        assert_eq!(simplify(&[(3, 3)]), vec![0]);
        assert_eq!(simplify(&[(3, 3), (4, 4)]), vec![0, 1]);
    }
}
