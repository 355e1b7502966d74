//! AprilTag 36h11 patterns as OpenCV draws them (`aruco::drawMarker` on the predefined
//! DICT_APRILTAG_36h11, the dictionary OpenCV 4.6's contrib aruco module carries; newer
//! OpenCV names these `getPredefinedDictionary` and `generateImageMarker` in objdetect),
//! each id drawn once and kept: what the twin paints on its floor and what the detector
//! reads back.

use crate::sim::tag_render::{MARKER_CELLS, TagCells};
use crate::tags::TagId;
use opencv::aruco;
use opencv::core::{Mat, Ptr};
use opencv::prelude::*;
use std::collections::BTreeMap;

/// The 36h11 dictionary and the patterns drawn from it so far.
pub struct TagPatterns {
    dictionary: Ptr<aruco::Dictionary>,
    drawn: BTreeMap<TagId, Option<TagCells>>,
}

impl std::fmt::Debug for TagPatterns {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "TagPatterns {{ {} drawn }}", self.drawn.len())
    }
}

/// OpenCV's AprilTag 36h11 dictionary.
pub fn dictionary() -> opencv::Result<Ptr<aruco::Dictionary>> {
    aruco::get_predefined_dictionary(aruco::PREDEFINED_DICTIONARY_NAME::DICT_APRILTAG_36h11)
}

impl TagPatterns {
    pub fn new() -> opencv::Result<Self> {
        Ok(Self {
            dictionary: dictionary()?,
            drawn: BTreeMap::new(),
        })
    }

    /// How many ids the dictionary holds (587 for 36h11).
    pub fn len(&self) -> usize {
        self.dictionary.bytes_list().rows().max(0) as usize
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Tag `id`'s cells, drawn by OpenCV the first time it is asked for: one pixel a
    /// cell, the black border included. None for an id the dictionary does not hold.
    pub fn cells(&mut self, id: TagId) -> Option<TagCells> {
        if let Some(known) = self.drawn.get(&id) {
            return *known;
        }
        let cells = self.draw(id);
        self.drawn.insert(id, cells);
        cells
    }

    /// The cells of every id of `ids` the dictionary holds.
    pub fn all(&mut self, ids: impl IntoIterator<Item = TagId>) -> BTreeMap<TagId, TagCells> {
        (ids.into_iter())
            .filter_map(|id| Some((id, self.cells(id)?)))
            .collect()
    }

    fn draw(&self, id: TagId) -> Option<TagCells> {
        let id = i32::try_from(id).ok()?;
        if usize::try_from(id).ok()? >= self.len() {
            return None;
        }
        let mut image = Mat::default();
        aruco::draw_marker(&self.dictionary, id, MARKER_CELLS as i32, &mut image, 1).ok()?;
        let bytes = image.data_bytes().ok()?;
        if bytes.len() != MARKER_CELLS * MARKER_CELLS {
            return None;
        }
        Some(std::array::from_fn(|k| bytes[k] > 127))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn patterns_have_a_black_border_differ_by_id_and_stop_at_the_dictionarys_end() {
        let mut p = TagPatterns::new().unwrap();
        assert_eq!(p.len(), 587);
        let a = p.cells(101).unwrap();
        let b = p.cells(508).unwrap();
        assert_ne!(a, b);
        for k in 0..MARKER_CELLS {
            for cell in [
                k,
                k * MARKER_CELLS,
                k * MARKER_CELLS + 7,
                7 * MARKER_CELLS + k,
            ] {
                assert!(!a[cell], "border cell {cell} is white");
            }
        }
        // 36h11's codes are 36 bits at least 11 apart: tags 101 and 508 differ in at
        // least 11 data cells.
        let differ = a.iter().zip(&b).filter(|(x, y)| x != y).count();
        assert!(differ >= 11, "{differ}");
        assert_eq!(p.cells(587), None);
        assert_eq!(p.cells(u32::MAX), None);
        assert_eq!(p.all([101, 9999]).len(), 1);
    }
}
