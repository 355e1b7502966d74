//! A second look at a decoded marker's cells. Seed 001's dictionary (ArUco original)
//! corrects no bit errors and its codes lie close together, so one cell misread turns a
//! marker into another valid ID. Every cell of the 7 x 7 square, and the white margin
//! round it, is read again at its middle through the homography of the refined corners,
//! and the marker is kept only when each cell is clearly the colour its ID says.

use super::edge_fit::median;
use super::frame::GrayFrame;

/// Cells across the black square, border included.
pub const CELLS: usize = 7;
/// A cell must lie this share of the black-white contrast away from the middle grey.
const CLEAR: f64 = 0.2;
/// Offsets of the points read in each cell, in cells from its middle.
const SPOTS: [f64; 3] = [-0.15, 0.0, 0.15];

/// Whether the cells of `frame` under the marker with corners `corners` (clockwise from
/// top-left) match `expected` (row-major, `true` for white), given `homography`, the
/// 3 x 3 row-major map from the unit square (0..1 across the black square) to the image.
pub fn cells_match(frame: &GrayFrame, homography: &[[f64; 3]; 3], expected: &[bool]) -> bool {
    debug_assert_eq!(expected.len(), CELLS * CELLS);
    let cell = 1.0 / CELLS as f64;
    // The mean grey of the cell whose middle is at (u, v) in the unit square.
    let read = |u: f64, v: f64| -> Option<f64> {
        let mut sum = 0.0;
        for dy in SPOTS {
            for dx in SPOTS {
                let (x, y) = apply(homography, u + dx * cell, v + dy * cell)?;
                sum += frame.sample(x, y)?;
            }
        }
        Some(sum / (SPOTS.len() * SPOTS.len()) as f64)
    };
    let middle = |i: usize| (i as f64 + 0.5) * cell;
    let Some(cells) = (0..CELLS * CELLS)
        .map(|k| read(middle(k % CELLS), middle(k / CELLS)))
        .collect::<Option<Vec<f64>>>()
    else {
        return false;
    };
    // The white margin: the ring of cells just outside the square.
    let ring = (0..CELLS).flat_map(|i| {
        let (a, o) = (middle(i), -0.5 * cell);
        [(a, o), (a, 1.0 - o), (o, a), (1.0 - o, a)]
    });
    // Cells of it outside the frame are left out; half of it must be there.
    let mut margin: Vec<f64> = ring.filter_map(|(u, v)| read(u, v)).collect();
    if margin.len() < 2 * CELLS {
        return false;
    }
    let Some(light) = median(&mut margin) else {
        return false;
    };
    let mut border: Vec<f64> = (0..CELLS * CELLS)
        .filter(|k| {
            let (c, r) = (k % CELLS, k / CELLS);
            c == 0 || r == 0 || c == CELLS - 1 || r == CELLS - 1
        })
        .map(|k| cells[k])
        .collect();
    let Some(dark) = median(&mut border) else {
        return false;
    };
    let contrast = light - dark;
    if contrast <= 0.0 {
        return false;
    }
    let mid = (light + dark) / 2.0;
    let margin_ok = margin.iter().all(|&g| g - mid >= CLEAR * contrast);
    margin_ok
        && cells.iter().zip(expected).all(|(&g, &white)| {
            let lean = if white { g - mid } else { mid - g };
            lean >= CLEAR * contrast
        })
}

/// Image point of the unit-square point (u, v): (x, y, w) = H (u, v, 1) (Hartley &
/// Zisserman 2.3); `None` behind the camera.
fn apply(h: &[[f64; 3]; 3], u: f64, v: f64) -> Option<(f64, f64)> {
    let w = h[2][0] * u + h[2][1] * v + h[2][2];
    if w.abs() < 1e-12 {
        return None;
    }
    Some((
        (h[0][0] * u + h[0][1] * v + h[0][2]) / w,
        (h[1][0] * u + h[1][1] * v + h[1][2]) / w,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A frame with a 7 x 7 marker of `pattern`, 6 px a cell, at (12, 12), on white.
    fn marker(pattern: &[bool]) -> GrayFrame {
        let mut frame = GrayFrame::filled(66, 66, 220);
        for (k, &white) in pattern.iter().enumerate() {
            let (c, r) = (k % CELLS, k / CELLS);
            for y in 0..6 {
                for x in 0..6 {
                    frame.data[(12 + r * 6 + y) * 66 + 12 + c * 6 + x] =
                        if white { 220 } else { 30 };
                }
            }
        }
        frame
    }

    /// The square from (11.5, 11.5) to (53.5, 53.5): pixel edges in pixel-centre terms.
    const H: [[f64; 3]; 3] = [[42.0, 0.0, 11.5], [0.0, 42.0, 11.5], [0.0, 0.0, 1.0]];

    fn pattern() -> Vec<bool> {
        (0..49)
            .map(|k| {
                let (c, r) = (k % 7, k / 7);
                let inner = c > 0 && r > 0 && c < 6 && r < 6;
                inner && (c + 2 * r) % 3 == 0
            })
            .collect()
    }

    #[test]
    fn the_cells_of_the_right_marker_match() {
        assert!(cells_match(&marker(&pattern()), &H, &pattern()));
    }

    #[test]
    fn one_cell_read_differently_is_a_mismatch() {
        let mut other = pattern();
        other[2 * 7 + 3] = !other[2 * 7 + 3];
        assert!(!cells_match(&marker(&pattern()), &H, &other));
    }

    #[test]
    fn a_grey_cell_or_a_dark_margin_is_a_mismatch() {
        let mut frame = marker(&pattern());
        // Half a cell of grey over the middle cell (3, 3): neither black nor white.
        for y in 30..36 {
            for x in 30..36 {
                frame.data[y * 66 + x] = 125;
            }
        }
        assert!(!cells_match(&frame, &H, &pattern()));
        let mut frame = marker(&pattern());
        // Something dark against the left side.
        for y in 0..66 {
            for x in 0..12 {
                frame.data[y * 66 + x] = 30;
            }
        }
        assert!(!cells_match(&frame, &H, &pattern()));
    }
}
