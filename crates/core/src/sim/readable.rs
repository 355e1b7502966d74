//! Which parts of a rendered frame the detector needs, worked out from where the markers
//! project: the regions round every marker whose sighting the detector could accept, and
//! the markers that reach into those regions. Pixels elsewhere cannot change a sighting,
//! so a frame drawn and detected only there gives the sightings the whole frame gives.
//! Squares are looked for in smaller windows, round the black squares alone; the rest of
//! a region is there for the corner refinement, which looks into the white round them.
//!
//! A marker's sighting is refused (`perception::aruco`) when its square is not wholly
//! inside the frame (OpenCV drops a square within 3 px of the border), is measured
//! further than `max_range`, or has a side shorter than `min_side_px`. A marker is left
//! out only when the truth is well past those limits, so that no measurement error could
//! bring it back: a square found in a frame can have a corner a little beyond the
//! border, as the blurred tip of a sharp corner is cut off before the square is traced.

use crate::perception::region::{Region, disjoint};

/// A marker is left out when its true range exceeds the detector's limit by this factor.
const RANGE_SLACK: f64 = 1.25;
/// ... or its true side is shorter than the detector's least side by this factor.
const SIDE_SLACK: f64 = 0.75;
/// ... or a corner of its square lies further outside the frame than this many pixels,
/// or half a cell of the marker if that is more.
const EDGE_SLACK_PX: f64 = 8.0;
/// Cells across a marker's black square.
const CELLS: f64 = 7.0;
/// Pixels round a readable marker's sheet, and round its square, that detection looks
/// at besides, on top of half the largest adaptive-threshold window (the threshold of a
/// pixel depends on the pixels within half a window of it): one for the square's outline
/// and 3 that OpenCV keeps a square from the edge of the image it searches.
const EXTRA_MARGIN: usize = 4;

/// Where one marker projects into the frame.
#[derive(Clone, Copy, Debug)]
pub struct Footprint {
    /// The pixels its paste writes: its sheet's bounding box inside the frame.
    pub sheet: Region,
    /// Image corners of its black square, pixels.
    pub square: [[f64; 2]; 4],
    /// True planar range from the robot centre, metres.
    pub range: f64,
}

/// What the detector refuses, from `[vision.detector]`.
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    pub max_range: f64,
    pub min_side_px: f64,
    /// The largest adaptive-threshold window, pixels.
    pub threshold_window: usize,
}

/// The regions to draw, the windows to search for squares, and which markers to draw.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Plan {
    pub regions: Vec<Region>,
    /// Inside the regions.
    pub windows: Vec<Region>,
    /// Per footprint: whether its sheet reaches into a region.
    pub draw: Vec<bool>,
}

impl Footprint {
    /// The black square's bounding box in a `width` x `height` frame.
    fn square_box(&self, width: usize, height: usize) -> Region {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in &self.square {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let clamp = |v: f64, limit: usize| v.clamp(0.0, limit as f64) as usize;
        Region {
            x0: clamp(lo[0].floor(), width),
            y0: clamp(lo[1].floor(), height),
            x1: clamp(hi[0].ceil() + 1.0, width),
            y1: clamp(hi[1].ceil() + 1.0, height),
        }
    }

    /// Whether the detector could accept a sighting of this marker in a `width` x
    /// `height` frame.
    pub fn readable(&self, width: usize, height: usize, limits: &Limits) -> bool {
        let sides = (0..4).map(|i| {
            let (a, b) = (self.square[i], self.square[(i + 1) % 4]);
            (a[0] - b[0]).hypot(a[1] - b[1])
        });
        let (side, longest) = sides.fold((f64::INFINITY, 0.0f64), |(lo, hi), s| {
            (lo.min(s), hi.max(s))
        });
        let slack = EDGE_SLACK_PX.max(longest / CELLS / 2.0);
        let (w, h) = (width as f64 - 1.0 + slack, height as f64 - 1.0 + slack);
        let inside = self
            .square
            .iter()
            .all(|&[u, v]| (-slack..=w).contains(&u) && (-slack..=h).contains(&v));
        inside
            && self.range <= RANGE_SLACK * limits.max_range
            && side >= SIDE_SLACK * limits.min_side_px
    }
}

/// The regions round the readable markers of a `width` x `height` frame and the windows
/// round their squares (each merged where they overlap), and the markers whose sheets
/// reach into the regions.
pub fn plan(footprints: &[Footprint], width: usize, height: usize, limits: &Limits) -> Plan {
    let margin = limits.threshold_window / 2 + EXTRA_MARGIN;
    let readable: Vec<&Footprint> = footprints
        .iter()
        .filter(|f| f.readable(width, height, limits))
        .collect();
    let grown = |r: Region| r.grown(margin, width, height);
    let regions = disjoint(readable.iter().map(|f| grown(f.sheet)));
    let windows = disjoint(readable.iter().map(|f| grown(f.square_box(width, height))));
    let draw = footprints
        .iter()
        .map(|f| regions.iter().any(|r| r.overlaps(&f.sheet)))
        .collect();
    Plan {
        regions,
        windows,
        draw,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LIMITS: Limits = Limits {
        max_range: 3.0,
        min_side_px: 12.0,
        threshold_window: 17,
    };

    /// A face-on marker whose square has `side` pixels, top-left at (x, y).
    fn at(x: f64, y: f64, side: f64, range: f64) -> Footprint {
        let q = side * 2.0 / 7.0;
        let sheet = Region {
            x0: (x - q).floor().max(0.0) as usize,
            y0: (y - q).floor().max(0.0) as usize,
            x1: ((x + side + q).ceil() + 1.0).clamp(0.0, 864.0) as usize,
            y1: ((y + side + q).ceil() + 1.0).clamp(0.0, 480.0) as usize,
        };
        Footprint {
            sheet,
            square: [[x, y], [x + side, y], [x + side, y + side], [x, y + side]],
            range,
        }
    }

    #[test]
    fn cut_off_far_or_tiny_markers_are_unreadable() {
        assert!(at(100.0, 100.0, 30.0, 1.0).readable(864, 480, &LIMITS));
        assert!(
            !at(-9.0, 100.0, 30.0, 1.0).readable(864, 480, &LIMITS),
            "cut by the left edge"
        );
        assert!(
            !at(845.0, 100.0, 30.0, 1.0).readable(864, 480, &LIMITS),
            "cut by the right edge"
        );
        assert!(
            at(838.0, 100.0, 30.0, 1.0).readable(864, 480, &LIMITS),
            "a corner just beyond the edge"
        );
        assert!(
            !at(100.0, -40.0, 140.0, 0.3).readable(864, 480, &LIMITS),
            "a big marker cut by the top"
        );
        assert!(
            at(100.0, -9.0, 140.0, 0.3).readable(864, 480, &LIMITS),
            "within half a 20 px cell"
        );
        assert!(
            !at(100.0, 100.0, 30.0, 3.9).readable(864, 480, &LIMITS),
            "too far"
        );
        assert!(
            at(100.0, 100.0, 30.0, 3.5).readable(864, 480, &LIMITS),
            "near enough to be misjudged"
        );
        assert!(
            !at(100.0, 100.0, 8.0, 1.0).readable(864, 480, &LIMITS),
            "too small"
        );
        assert!(
            at(100.0, 100.0, 10.0, 1.0).readable(864, 480, &LIMITS),
            "small enough to be misjudged"
        );
    }

    #[test]
    fn a_frame_without_readable_markers_needs_nothing() {
        let p = plan(&[at(-10.0, 10.0, 60.0, 0.5)], 864, 480, &LIMITS);
        assert!(p.regions.is_empty());
        assert_eq!(p.draw, vec![false]);
    }

    #[test]
    fn markers_reaching_into_a_region_are_drawn_and_the_rest_are_not() {
        let readable = at(100.0, 100.0, 40.0, 1.0);
        // Cut by the top edge, but its sheet overlaps the readable one's surroundings.
        let neighbour = at(150.0, -10.0, 70.0, 0.8);
        let apart = at(600.0, -20.0, 60.0, 0.8);
        let p = plan(&[readable, neighbour, apart], 864, 480, &LIMITS);
        assert_eq!(p.regions.len(), 1);
        let r = p.regions[0];
        assert!(r.x0 <= readable.sheet.x0 - 12 && r.x1 >= readable.sheet.x1 + 12);
        assert_eq!(p.draw, vec![true, true, false]);
        // The square's window: 12 px round the square, inside the region.
        assert_eq!(
            p.windows,
            vec![Region {
                x0: 88,
                y0: 88,
                x1: 153,
                y1: 153
            }]
        );
        assert!(p.windows[0].intersection(&r) == Some(p.windows[0]));
    }
}
