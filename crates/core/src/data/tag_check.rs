//! The frame check's part for floor tags (`SensorFrame::tags`): at most `MAX_TAGS` a
//! frame, each offset finite and within `MAX_TAG_OFFSET`, each angle finite (then
//! wrapped). A bad sighting is taken out and named; the rest are kept.

use super::frame_check::{Refused, check_list, short};
use super::sensors::SensorFrame;
use crate::geometry::wrap_angle;

/// Tags in one frame at most: AprilTag 36h11 holds 587 codes, each seen once a frame.
pub const MAX_TAGS: usize = 587;
/// A tag farther than this from the image centre's floor point is a bad reading, metres:
/// a camera looking down at the floor sees a metre or two of it.
pub const MAX_TAG_OFFSET: f64 = 10.0;

/// Checks `frame.tags` in place, adding what it took out to `refused`.
pub(super) fn check_tags(frame: &mut SensorFrame, refused: &mut Vec<Refused>) {
    let offset_bound = format!("must be finite, within ±{} m", short(MAX_TAG_OFFSET));
    check_list(&mut frame.tags, "tags", MAX_TAGS, refused, |s| {
        let offsets = [("tags.ahead", s.ahead), ("tags.lateral", s.lateral)];
        match offsets
            .into_iter()
            .find(|(_, v)| !(0.0..=MAX_TAG_OFFSET).contains(&v.abs()))
        {
            Some((field, value)) => Some(Refused::new(field, value, offset_bound.clone())),
            None if !s.align.is_finite() => {
                Some(Refused::new("tags.align", s.align, "must be finite"))
            }
            None => {
                s.align = wrap_angle(s.align);
                None
            }
        }
    });
}

#[cfg(test)]
mod tests {
    use super::super::frame_check::check_frame;
    use super::*;
    use crate::data::TagSighting;

    fn seen(id: u32, ahead: f64, lateral: f64, align: f64) -> TagSighting {
        TagSighting {
            id,
            ahead,
            lateral,
            align,
        }
    }

    #[test]
    fn non_finite_or_far_tags_are_taken_out_and_named_the_rest_kept() {
        let mut frame = SensorFrame {
            tags: Some(vec![
                seen(101, f64::NAN, 0.0, 0.0),
                seen(102, 0.02, 0.01, 0.0),
                seen(103, 0.0, 1e9, 0.0),
                seen(104, 0.0, 0.0, f64::INFINITY),
            ]),
            ..SensorFrame::default()
        };
        let refused = check_frame(&mut frame, 1.0).unwrap();
        // The first bad sighting is named with its field; the others go with it.
        assert_eq!(refused.len(), 1, "{refused:?}");
        assert_eq!(refused[0].field, "tags.ahead");
        let kept = frame.tags.unwrap();
        assert_eq!(kept.iter().map(|s| s.id).collect::<Vec<_>>(), [102]);
        let mut angle = SensorFrame {
            tags: Some(vec![seen(7, 0.0, 0.0, f64::NAN)]),
            ..SensorFrame::default()
        };
        let refused = check_frame(&mut angle, 1.0).unwrap();
        assert_eq!(refused[0].field, "tags.align");
        assert_eq!(angle.tags, Some(vec![]));
    }

    #[test]
    fn too_many_tags_drop_the_list() {
        let mut frame = SensorFrame {
            tags: Some(vec![seen(1, 0.0, 0.0, 0.0); MAX_TAGS + 1]),
            ..SensorFrame::default()
        };
        let refused = check_frame(&mut frame, 1.0).unwrap();
        assert_eq!(refused[0].field, "tags");
        assert_eq!(frame.tags, None);
    }
}
