//! Sliding windows up a bird's-eye mask of one lane line and the quadratic fitted through
//! the cells they collect (seed 000 §2.2.1-§2.2.2).

/// A binary bird's-eye mask, one byte a cell, rows from the far edge down.
#[derive(Clone, Copy, Debug)]
pub struct GridMask<'a> {
    pub cols: usize,
    pub rows: usize,
    pub data: &'a [u8],
}

impl GridMask<'_> {
    fn lit(&self, col: usize, row: usize) -> bool {
        self.data[row * self.cols + col] != 0
    }
}

/// How the windows search.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WindowSearch {
    pub windows: usize,
    /// A window's base width, millimetres.
    pub base_width_mm: f64,
    /// Millimetres per cell.
    pub cell_mm: f64,
}

/// A line found by the windows: x = a y^2 + b y + c in millimetres of the grid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineFound {
    pub fit: [f64; 3],
    /// The share of windows that found the line.
    pub confidence: f64,
}

/// Fewest lit cells for a window to count as finding the line.
const MIN_CELLS: usize = 8;
/// Fewest windows that must find the line before it is fitted.
const MIN_WINDOWS: usize = 3;

/// seed 000 §2.2.2 `update_window_size`: narrow to 0.8x over density 0.8, widen to 1.5x
/// under 0.3. The density is the share of the window's rows that hold the line.
fn width_factor(density: f64) -> f64 {
    if density > 0.8 {
        0.8
    } else if density < 0.3 {
        1.5
    } else {
        1.0
    }
}

/// Least-squares x = a y^2 + b y + c through `points` (y, x), none if they do not fix a
/// parabola. Solved in metres (y / 1000) for conditioning, returned in millimetres.
pub fn fit_quadratic(points: &[(f64, f64)], weights: Option<&[f64]>) -> Option<[f64; 3]> {
    use nalgebra::{Matrix3, Vector3};
    if !three_rows(points) {
        return None;
    }
    let mut normal = Matrix3::<f64>::zeros();
    let mut rhs = Vector3::<f64>::zeros();
    for (i, &(y, x)) in points.iter().enumerate() {
        let w = weights.map_or(1.0, |w| w[i]);
        let s = y / 1000.0;
        let row = Vector3::new(s * s, s, 1.0);
        // Normal equations A^T W A p = A^T W x (Golub & Van Loan 5.3).
        normal += w * row * row.transpose();
        rhs += w * x * row;
    }
    let p = normal.lu().solve(&rhs)?;
    p.iter()
        .all(|v| v.is_finite())
        .then(|| [p[0] / 1e6, p[1] / 1e3, p[2]])
}

/// Whether `points` lie on at least three different rows, as a parabola needs.
fn three_rows(points: &[(f64, f64)]) -> bool {
    let Some(&(first, _)) = points.first() else {
        return false;
    };
    let Some(&(second, _)) = points.iter().find(|p| p.0 != first) else {
        return false;
    };
    points.iter().any(|p| p.0 != first && p.0 != second)
}

/// x of `fit` at row `y`.
pub fn x_at(fit: &[f64; 3], y: f64) -> f64 {
    fit[0] * y * y + fit[1] * y + fit[2]
}

/// The column (in cells) where the line starts: the peak of the lit-cell count per column
/// over the near half of the mask, or over all of it when the near half is empty.
fn base_column(mask: &GridMask) -> Option<usize> {
    let count = |rows: std::ops::Range<usize>| {
        let mut h = vec![0usize; mask.cols];
        for r in rows {
            for (c, n) in h.iter_mut().enumerate() {
                *n += usize::from(mask.lit(c, r));
            }
        }
        h
    };
    let peak = |h: &[usize]| {
        let (c, &n) = h
            .iter()
            .enumerate()
            .max_by_key(|&(c, n)| (*n, usize::MAX - c))?;
        (n >= MIN_CELLS / 2).then_some(c)
    };
    peak(&count(mask.rows / 2..mask.rows)).or_else(|| peak(&count(0..mask.rows)))
}

/// seed 000 §2.2.2 `predict_next_center`: the last centre with fewer than three, else a
/// quadratic through the centres so far evaluated at the next window's row.
fn predict(centres: &[(f64, f64)], next_y: f64) -> Option<f64> {
    match centres {
        [] => None,
        [.., last] if centres.len() < 3 => Some(last.1),
        _ => fit_quadratic(centres, None).map(|f| x_at(&f, next_y)),
    }
}

/// Slides windows from the near edge of `mask` to the far one and fits the line they
/// follow; none when too few windows find it.
pub fn find_line(mask: &GridMask, search: &WindowSearch) -> Option<LineFound> {
    let cell = search.cell_mm;
    let mut centre = base_column(mask)? as f64 + 0.5;
    let mut width = search.base_width_mm / cell;
    let mut centres: Vec<(f64, f64)> = Vec::new();
    let mut cells: Vec<(f64, f64)> = Vec::new();
    let n = search.windows.max(1);
    for w in 0..n {
        // Window w covers rows [top, bottom), counted up from the near edge.
        let bottom = mask.rows - w * mask.rows / n;
        let top = mask.rows - (w + 1) * mask.rows / n;
        let left = (centre - width / 2.0).max(0.0) as usize;
        let right = ((centre + width / 2.0).max(0.0) as usize).min(mask.cols);
        let (mut sum, mut found, mut rows_lit) = (0.0, 0usize, 0usize);
        for r in top..bottom {
            let before = found;
            for c in left..right {
                if mask.lit(c, r) {
                    sum += c as f64 + 0.5;
                    found += 1;
                    cells.push(((r as f64 + 0.5) * cell, (c as f64 + 0.5) * cell));
                }
            }
            rows_lit += usize::from(found > before);
        }
        let mid = (top + bottom) as f64 / 2.0 * cell;
        if found >= MIN_CELLS {
            centres.push((mid, sum / found as f64 * cell));
        } else {
            cells.truncate(cells.len() - found);
        }
        let density = rows_lit as f64 / (bottom - top).max(1) as f64;
        width = search.base_width_mm / cell * width_factor(density);
        let next_y = mid - (bottom - top) as f64 * cell;
        if let Some(x) = predict(&centres, next_y) {
            // The prediction may not leave the window it came from by more than its width.
            let last = centres.last().map_or(centre, |c| c.1 / cell);
            centre = (x / cell).clamp(last - width, last + width);
        }
    }
    if centres.len() < MIN_WINDOWS {
        return None;
    }
    let fit = fit_quadratic(&cells, None)?;
    Some(LineFound {
        fit,
        confidence: centres.len() as f64 / n as f64,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 100 x 80 mask (4 mm cells) with a 6-cell-wide line along x = f(y), gaps where
    /// `gap(y)` holds.
    fn mask(f: impl Fn(f64) -> f64, gap: impl Fn(f64) -> bool) -> Vec<u8> {
        let mut m = vec![0u8; 100 * 80];
        for r in 0..80 {
            let y = (r as f64 + 0.5) * 4.0;
            if gap(y) {
                continue;
            }
            for c in 0..100 {
                let x = (c as f64 + 0.5) * 4.0;
                if (x - f(y)).abs() < 12.0 {
                    m[r * 100 + c] = 255;
                }
            }
        }
        m
    }

    const SEARCH: WindowSearch = WindowSearch {
        windows: 8,
        base_width_mm: 100.0,
        cell_mm: 4.0,
    };

    #[test]
    fn windows_follow_a_curving_dashed_line_and_fit_it() {
        // x = 0.001 y^2 - 0.2 y + 250 mm, dashes of 40 mm every 80 mm.
        let f = |y: f64| 0.001 * y * y - 0.2 * y + 250.0;
        let data = mask(f, |y| (y / 40.0) as usize % 2 == 1);
        let grid = GridMask {
            cols: 100,
            rows: 80,
            data: &data,
        };
        let line = find_line(&grid, &SEARCH).unwrap();
        for y in [20.0, 160.0, 300.0] {
            assert!(
                (x_at(&line.fit, y) - f(y)).abs() < 3.0,
                "{y}: {:?}",
                line.fit
            );
        }
        assert!(
            line.confidence >= 0.5 && line.confidence <= 1.0,
            "{}",
            line.confidence
        );
    }

    #[test]
    fn an_empty_mask_has_no_line() {
        let data = vec![0u8; 100 * 80];
        let grid = GridMask {
            cols: 100,
            rows: 80,
            data: &data,
        };
        assert_eq!(find_line(&grid, &SEARCH), None);
        assert_eq!(fit_quadratic(&[(1.0, 1.0), (1.0, 2.0)], None), None);
    }
}
