//! A rectangle of a frame's pixels, for work that only part of a frame needs.

/// Columns `x0..x1` of rows `y0..y1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Region {
    pub x0: usize,
    pub y0: usize,
    pub x1: usize,
    pub y1: usize,
}

impl Region {
    /// All of a `width` x `height` frame.
    pub fn whole(width: usize, height: usize) -> Region {
        Region {
            x0: 0,
            y0: 0,
            x1: width,
            y1: height,
        }
    }

    pub fn width(&self) -> usize {
        self.x1.saturating_sub(self.x0)
    }

    pub fn height(&self) -> usize {
        self.y1.saturating_sub(self.y0)
    }

    pub fn is_empty(&self) -> bool {
        self.width() == 0 || self.height() == 0
    }

    /// True when the two share a pixel.
    pub fn overlaps(&self, other: &Region) -> bool {
        self.x0 < other.x1 && other.x0 < self.x1 && self.y0 < other.y1 && other.y0 < self.y1
    }

    /// The pixels in both, if any.
    pub fn intersection(&self, other: &Region) -> Option<Region> {
        let r = Region {
            x0: self.x0.max(other.x0),
            y0: self.y0.max(other.y0),
            x1: self.x1.min(other.x1),
            y1: self.y1.min(other.y1),
        };
        (!r.is_empty()).then_some(r)
    }

    /// The smallest region holding both.
    pub fn union(&self, other: &Region) -> Region {
        Region {
            x0: self.x0.min(other.x0),
            y0: self.y0.min(other.y0),
            x1: self.x1.max(other.x1),
            y1: self.y1.max(other.y1),
        }
    }

    /// Grown by `margin` pixels on every side, kept inside a `width` x `height` frame.
    pub fn grown(&self, margin: usize, width: usize, height: usize) -> Region {
        Region {
            x0: self.x0.saturating_sub(margin),
            y0: self.y0.saturating_sub(margin),
            x1: (self.x1 + margin).min(width),
            y1: (self.y1 + margin).min(height),
        }
    }
}

/// `regions` merged until no two overlap: each pixel of the input is in exactly one of
/// the output, and the output covers nothing more than bounding boxes of overlapping input.
pub fn disjoint(regions: impl IntoIterator<Item = Region>) -> Vec<Region> {
    let mut out: Vec<Region> = Vec::new();
    for mut r in regions.into_iter().filter(|r| !r.is_empty()) {
        // A merged box may overlap boxes it did not before: merge until it stands alone.
        while let Some(i) = out.iter().position(|o| o.overlaps(&r)) {
            r = r.union(&out.swap_remove(i));
        }
        out.push(r);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn r(x0: usize, y0: usize, x1: usize, y1: usize) -> Region {
        Region { x0, y0, x1, y1 }
    }

    #[test]
    fn overlapping_boxes_merge_and_apart_ones_stay_apart() {
        let out = disjoint([r(0, 0, 10, 10), r(50, 50, 60, 60), r(8, 8, 20, 12)]);
        assert_eq!(out.len(), 2);
        assert!(out.contains(&r(0, 0, 20, 12)));
        assert!(out.contains(&r(50, 50, 60, 60)));
        // A merge that reaches a third box takes it in too.
        let out = disjoint([r(0, 0, 10, 10), r(20, 0, 30, 10), r(5, 5, 25, 6)]);
        assert_eq!(out, vec![r(0, 0, 30, 10)]);
        // Touching edges share no pixel.
        assert_eq!(disjoint([r(0, 0, 10, 10), r(10, 0, 20, 10)]).len(), 2);
    }

    #[test]
    fn growing_stays_inside_the_frame() {
        assert_eq!(r(2, 3, 10, 10).grown(5, 12, 100), r(0, 0, 12, 15));
        assert!(r(4, 4, 4, 9).is_empty());
        assert_eq!(
            r(0, 0, 10, 10).intersection(&r(5, 8, 20, 20)),
            Some(r(5, 8, 10, 10))
        );
        assert_eq!(r(0, 0, 10, 10).intersection(&r(10, 0, 20, 10)), None);
    }
}
