//! A tag painted on the floor: its cells as OpenCV draws the 36h11 pattern (a black
//! border round 6x6 data cells), a white border one cell wide round that, and each pixel
//! over a cell edge the mean of 4x4 samples across it (supersampled anti-aliasing), so a
//! corner falls where the pinhole puts it to a fraction of a pixel.

use super::floor::{FloorShade, FrameLight};
use super::projection::FloorView;
use crate::tags::TagId;

/// Cells along a side of the marker: 6 data cells and the black border (36h11).
pub const MARKER_CELLS: usize = 8;
/// Cells along a side of the printed tag: the marker and its white border.
const PRINTED_CELLS: i64 = MARKER_CELLS as i64 + 2;
/// Samples along each side of a pixel over an edge.
const SUPERSAMPLE: usize = 4;

/// A marker's cells, row by row from its top-left corner: true for white.
pub type TagCells = [bool; MARKER_CELLS * MARKER_CELLS];

/// What lies at a floor point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ink {
    Floor,
    White,
    Black,
}

/// One tag on the floor.
#[derive(Clone, Debug)]
pub struct FloorTag {
    pub id: TagId,
    pub centre: [f64; 2],
    /// The way the marker's top faces on the floor (unit vector): its zone's heading.
    pub up: [f64; 2],
    pub cells: TagCells,
}

impl FloorTag {
    /// The ink at floor point `p`, for a tag of cells `cell` metres wide.
    #[inline]
    pub fn ink(&self, p: [f64; 2], cell: f64) -> Ink {
        let (dx, dy) = (p[0] - self.centre[0], p[1] - self.centre[1]);
        let [ux, uy] = self.up;
        // Across the marker (its right, the up vector turned a quarter clockwise) and up it.
        let (across, along) = (dx * uy - dy * ux, dx * ux + dy * uy);
        let half = PRINTED_CELLS as f64 / 2.0;
        let col = (across / cell + half).floor() as i64;
        let row = (half - along / cell).floor() as i64;
        if !(0..PRINTED_CELLS).contains(&col) || !(0..PRINTED_CELLS).contains(&row) {
            return Ink::Floor;
        }
        if col == 0 || row == 0 || col == PRINTED_CELLS - 1 || row == PRINTED_CELLS - 1 {
            return Ink::White;
        }
        let index = (row as usize - 1) * MARKER_CELLS + (col as usize - 1);
        if self.cells[index] {
            Ink::White
        } else {
            Ink::Black
        }
    }

    /// The printed square's corners on the floor, for a tag of cells `cell` metres wide.
    pub fn printed_corners(&self, cell: f64) -> [[f64; 2]; 4] {
        self.corners(cell * PRINTED_CELLS as f64 / 2.0)
    }

    /// The black square's corners, clockwise from the marker's top-left as seen from
    /// above (OpenCV's corner order).
    pub fn marker_corners(&self, cell: f64) -> [[f64; 2]; 4] {
        self.corners(cell * MARKER_CELLS as f64 / 2.0)
    }

    fn corners(&self, half: f64) -> [[f64; 2]; 4] {
        let [ux, uy] = self.up;
        let (rx, ry) = (uy, -ux);
        let [cx, cy] = self.centre;
        [(-1.0, 1.0), (1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)]
            .map(|(a, b)| [cx + half * (a * rx + b * ux), cy + half * (a * ry + b * uy)])
    }
}

/// Grey levels of a tag's ink under full light.
#[derive(Clone, Copy, Debug)]
pub struct InkLevels {
    pub black: f32,
    pub white: f32,
}

/// What a frame is painted with.
pub struct Canvas<'a> {
    pub view: &'a FloorView,
    pub light: &'a FrameLight,
    pub shade: &'a FloorShade,
    pub levels: InkLevels,
    pub cell: f64,
}

impl Canvas<'_> {
    /// The grey of `ink` at floor point `p` seen at pixel (`u`, `v`).
    #[inline]
    fn grey(&self, ink: Ink, p: [f64; 2], u: f32, v: f32) -> f32 {
        let base = match ink {
            Ink::Floor => self.shade.grey(p),
            Ink::White => self.levels.white,
            Ink::Black => self.levels.black,
        };
        base * self.light.at(u, v)
    }

    /// Paints `tag` over the floor already in `pixels` (rows of `view.width()`).
    pub fn paint(&self, tag: &FloorTag, pixels: &mut [u8]) {
        let (w, h) = (self.view.width(), self.view.height());
        let Some((u0, v0, u1, v1)) = self.bounds(tag, w, h) else {
            return;
        };
        // The ink at each pixel's corners (grid points half a pixel off the centres).
        let gw = u1 - u0 + 2;
        let ink_at = |u: f64, v: f64| {
            (self.view.floor_at(u, v)).map_or(Ink::Floor, |p| tag.ink(p, self.cell))
        };
        let grid: Vec<Ink> = (0..(v1 - v0 + 2) * gw)
            .map(|k| {
                let (i, j) = (k % gw, k / gw);
                ink_at((u0 + i) as f64 - 0.5, (v0 + j) as f64 - 0.5)
            })
            .collect();
        for v in v0..=v1 {
            for u in u0..=u1 {
                let (i, j) = (u - u0, v - v0);
                let corners = [
                    grid[j * gw + i],
                    grid[j * gw + i + 1],
                    grid[(j + 1) * gw + i],
                    grid[(j + 1) * gw + i + 1],
                ];
                let grey = if corners.iter().all(|&c| c == corners[0]) {
                    if corners[0] == Ink::Floor {
                        continue;
                    }
                    self.grey(corners[0], [0.0; 2], u as f32, v as f32)
                } else {
                    self.over_edge(tag, u as f64, v as f64)
                };
                // A cast saturates: rounded to the nearest level and held to 0..=255.
                pixels[v * w + u] = (grey + 0.5) as u8;
            }
        }
    }

    /// The mean grey of `SUPERSAMPLE`² samples spread evenly over pixel (`u`, `v`).
    fn over_edge(&self, tag: &FloorTag, u: f64, v: f64) -> f32 {
        let n = SUPERSAMPLE as f64;
        let mut sum = 0.0;
        for a in 0..SUPERSAMPLE {
            for b in 0..SUPERSAMPLE {
                let (su, sv) = (
                    u - 0.5 + (a as f64 + 0.5) / n,
                    v - 0.5 + (b as f64 + 0.5) / n,
                );
                let Some(p) = self.view.floor_at(su, sv) else {
                    continue;
                };
                sum += self.grey(tag.ink(p, self.cell), p, su as f32, sv as f32);
            }
        }
        sum / (SUPERSAMPLE * SUPERSAMPLE) as f32
    }

    /// The pixels the printed tag may cover, clipped to the image: (u0, v0, u1, v1)
    /// inclusive; None when it lies outside or reaches behind the lens.
    fn bounds(&self, tag: &FloorTag, w: usize, h: usize) -> Option<(usize, usize, usize, usize)> {
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for [x, y] in tag.printed_corners(self.cell) {
            let (u, v) = self.view.pixel_of(x, y)?;
            lo = [lo[0].min(u), lo[1].min(v)];
            hi = [hi[0].max(u), hi[1].max(v)];
        }
        let (wf, hf) = (w as f64 - 1.0, h as f64 - 1.0);
        if hi[0] < 0.0 || hi[1] < 0.0 || lo[0] > wf || lo[1] > hf {
            return None;
        }
        let clip = |x: f64, top: f64| x.clamp(0.0, top) as usize;
        Some((
            clip(lo[0].floor(), wf),
            clip(lo[1].floor(), hf),
            clip(hi[0].ceil(), wf),
            clip(hi[1].ceil(), hf),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tag(up: [f64; 2]) -> FloorTag {
        let mut cells = [false; MARKER_CELLS * MARKER_CELLS];
        // One white data cell: the marker's row 1, column 2.
        cells[MARKER_CELLS + 2] = true;
        FloorTag {
            id: 101,
            centre: [1.0, 2.0],
            up,
            cells,
        }
    }

    #[test]
    fn the_ink_follows_the_cells_with_the_marker_top_facing_up() {
        let cell = 0.01;
        let east = tag([1.0, 0.0]);
        assert_eq!(east.ink([1.0, 2.0], cell), Ink::Black);
        // The white border: printed cell 0 is 4.5 cells ahead of the centre (the top).
        assert_eq!(east.ink([1.045, 2.0], cell), Ink::White);
        assert_eq!(east.ink([1.055, 2.0], cell), Ink::Floor);
        // Marker row 1 (printed row 2) is 2.5 cells ahead of the centre; column 2
        // (printed 3) is 1.5 cells left of the centre across, i.e. to the north (+y)
        // when the top faces east.
        assert_eq!(east.ink([1.025, 2.015], cell), Ink::White);
        assert_eq!(east.ink([1.025, 1.985], cell), Ink::Black);
        // Facing north, the same cell lies 2.5 cells north and 1.5 west.
        let north = tag([0.0, 1.0]);
        assert_eq!(north.ink([0.985, 2.025], cell), Ink::White);
        // The marker's top-left corner is ahead and to the left.
        let [tl, tr, ..] = east.marker_corners(cell);
        assert!((tl[0] - 1.04).abs() < 1e-12 && (tl[1] - 2.04).abs() < 1e-12);
        assert!((tr[0] - 1.04).abs() < 1e-12 && (tr[1] - 1.96).abs() < 1e-12);
    }
}
