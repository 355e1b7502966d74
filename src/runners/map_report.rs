//! `navdeck map info` and `navdeck map show`: a map file described and drawn on stdout.

use crate::map::grid::{FREE, OCCUPIED, OccupancyGrid};
use crate::map::io::MapFile;
use serde::Serialize;

/// What `navdeck map info` prints.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MapInfo {
    pub width: usize,
    pub height: usize,
    pub resolution: f64,
    pub origin: [f64; 2],
    /// Extent in metres.
    pub size_m: [f64; 2],
    pub occupied: usize,
    pub free: usize,
    pub unknown: usize,
    pub landmarks: usize,
    pub created: Option<String>,
}

pub fn info(map: &MapFile) -> MapInfo {
    let g = &map.grid;
    let count = |f: &dyn Fn(i8) -> bool| g.cells.iter().filter(|&&v| f(v)).count();
    let occupied = count(&|v| v >= OCCUPIED / 2);
    let free = count(&|v| (FREE..OCCUPIED / 2).contains(&v));
    let extent = g.extent();
    MapInfo {
        width: g.width,
        height: g.height,
        resolution: g.resolution,
        origin: [g.origin.x, g.origin.y],
        size_m: [extent.0, extent.1],
        occupied,
        free,
        unknown: g.cells.len() - occupied - free,
        landmarks: map.extras.as_ref().map_or(0, |e| e.landmarks.len()),
        created: map.extras.as_ref().map(|e| e.created.clone()),
    }
}

pub fn human(i: &MapInfo) -> String {
    format!(
        "{} x {} cells at {} m ({:.2} m x {:.2} m), origin ({}, {})\n\
         occupied {}, free {}, unknown {}; {} landmarks{}\n",
        i.width,
        i.height,
        i.resolution,
        i.size_m[0],
        i.size_m[1],
        i.origin[0],
        i.origin[1],
        i.occupied,
        i.free,
        i.unknown,
        i.landmarks,
        i.created
            .as_ref()
            .map_or(String::new(), |c| format!("; saved {c}"))
    )
}

/// The grid as text `columns` wide, north up: '#' occupied, '.' free, ' ' unknown. A text
/// row covers twice a column's metres, as terminal cells are about twice as tall as wide.
pub fn show(grid: &OccupancyGrid, columns: usize) -> String {
    let (w, h) = grid.extent();
    let columns = columns.max(1);
    let step = w / columns as f64;
    let rows = ((h / (2.0 * step)).ceil() as usize).max(1);
    let mut out = String::with_capacity((columns + 1) * rows);
    for r in 0..rows {
        let top = grid.origin.y + h - r as f64 * 2.0 * step;
        for c in 0..columns {
            let left = grid.origin.x + c as f64 * step;
            out.push(
                match grid.max_in(left, top - 2.0 * step, left + step, top) {
                    v if v >= OCCUPIED / 2 => '#',
                    v if v >= FREE => '.',
                    _ => ' ',
                },
            );
        }
        while out.ends_with(' ') {
            out.pop();
        }
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Point2;

    #[test]
    fn a_small_room_is_drawn_and_counted() {
        let mut g = OccupancyGrid::new(4, 2, 0.5, Point2::new(0.0, 0.0), FREE);
        g.set(0, 1, OCCUPIED);
        g.set(3, 0, -1);
        let map = MapFile {
            grid: g.clone(),
            extras: None,
        };
        let i = info(&map);
        assert_eq!((i.occupied, i.free, i.unknown), (1, 6, 1));
        assert_eq!(i.size_m, [2.0, 1.0]);
        assert_eq!(show(&g, 4), "#...\n");
    }
}
