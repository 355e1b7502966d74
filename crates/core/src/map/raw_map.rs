//! A map_server image as read and checked, before its pixels become cells, and the one
//! pixel-to-cell reading that a map and a Nav2 filter mask share (thresholds, `negate`,
//! image rows top to bottom); they differ only in what `raw` and `scale` values mean.

use super::grid::{FREE, OCCUPIED, OccupancyGrid, UNKNOWN};
use super::io::Extras;
use super::pgm;
use crate::geometry::Point2;

/// map_server's `mode`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Mode {
    Trinary,
    Scale,
    Raw,
}

/// A map_server pair as read, checked, before its pixels become cells.
#[derive(Clone, Debug)]
pub struct RawMap {
    pub resolution: f64,
    pub origin: Point2,
    pub negate: bool,
    pub occupied_thresh: f64,
    pub free_thresh: f64,
    pub mode: Mode,
    pub image: pgm::Pgm,
    pub extras: Option<Extras>,
}

/// What the image's cells are read as.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Reading {
    /// An occupancy map: `raw` keeps pixels 0..=100, `scale` lays 1..99 between the
    /// thresholds, so a scaled cell is never read as free or occupied.
    Map,
    /// A Nav2 costmap filter mask: `raw` is the pixel's level on a 0..255 scale, `scale`
    /// spans 0..100 between the thresholds (nav2_map_server map_io loadMapFromFile).
    FilterMask,
}

impl RawMap {
    /// The image's cells as `reading` takes them: -1 unknown, else 0..=100.
    pub fn cells(&self, reading: Reading) -> OccupancyGrid {
        let image = &self.image;
        let (w, h) = (image.width, image.height);
        let mut grid = OccupancyGrid::new(w, h, self.resolution, self.origin, UNKNOWN);
        let max = f64::from(image.maxval);
        let (occupied, free) = (self.occupied_thresh, self.free_thresh);
        for (k, &pixel) in image.pixels.iter().enumerate() {
            let p = f64::from(pixel) / max;
            // map_server: occupancy = (255 - p) / 255, or p / 255 when negated.
            let occupancy = if self.negate { p } else { 1.0 - p };
            let value = match (self.mode, reading) {
                (Mode::Raw, Reading::Map) => i8::try_from(pixel)
                    .ok()
                    .filter(|v| *v <= OCCUPIED)
                    .unwrap_or(UNKNOWN),
                (Mode::Raw, Reading::FilterMask) => {
                    let v = (p * 255.0).round();
                    if (0.0..=100.0).contains(&v) {
                        v as i8
                    } else {
                        UNKNOWN
                    }
                }
                _ if occupancy > occupied => OCCUPIED,
                _ if occupancy < free => FREE,
                (Mode::Trinary, _) => UNKNOWN,
                (Mode::Scale, Reading::Map) => {
                    let t = (occupancy - free) / (occupied - free);
                    (1.0 + 98.0 * t).round() as i8
                }
                (Mode::Scale, Reading::FilterMask) => {
                    ((occupancy - free) / (occupied - free) * 100.0).round() as i8
                }
            };
            // Image rows run top to bottom; grid rows bottom to top.
            grid.set(k % w, h - 1 - k / w, value);
        }
        grid
    }
}
