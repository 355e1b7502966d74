//! The lit lamp of a traffic light (seed 000 §3.1): bright saturated blobs above the
//! horizon, kept when round (§3.1.3), coloured by the Bayesian classifier (§3.1.2), ranged
//! from their size.

use super::colour_bayes;
use super::shape::BlobShape;
use crate::data::LightSeen;
use crate::perception::intrinsics::Intrinsics;
use opencv::core::{self, Mat, Point, Rect, Scalar, Vector};
use opencv::imgproc;
use opencv::prelude::*;

/// Least saturation and brightness of a lit lamp (a lit lamp is vivid and bright).
const LIT_SATURATION: f64 = 100.0;
const LIT_VALUE: f64 = 150.0;
/// Least area of a lamp, pixels (a 2.5 cm lamp 2.5 m away is ~4 px across).
const MIN_AREA: f64 = 10.0;

/// Finds lit lamps in the rows above `bottom` of a frame.
pub struct LightFinder {
    /// Rows searched: from the top down to this one (the horizon plus a margin).
    pub bottom: i32,
    /// The camera, and the lamp's radius in metres, for the range.
    pub intrinsics: Intrinsics,
    pub lamp_radius: f64,
}

impl LightFinder {
    /// The most probable lit lamp in `hsv` (the whole frame in HSV), if any.
    pub fn find(&self, hsv: &Mat) -> opencv::Result<Option<LightSeen>> {
        let rows = self.bottom.clamp(0, hsv.rows());
        if rows == 0 {
            return Ok(None);
        }
        let roi = Mat::roi(hsv, Rect::new(0, 0, hsv.cols(), rows))?;
        let mut lit = Mat::default();
        core::in_range(
            &roi,
            &Scalar::new(0.0, LIT_SATURATION, LIT_VALUE, 0.0),
            &Scalar::new(180.0, 255.0, 255.0, 0.0),
            &mut lit,
        )?;
        let mut contours = Vector::<Vector<Point>>::new();
        imgproc::find_contours_def(
            &lit,
            &mut contours,
            imgproc::RETR_EXTERNAL,
            imgproc::CHAIN_APPROX_NONE,
        )?;
        let mut best: Option<(f64, LightSeen)> = None;
        for contour in &contours {
            let Some(shape) = BlobShape::of(&contour)? else {
                continue;
            };
            if shape.area < MIN_AREA || !shape.is_lamp() {
                continue;
            }
            let hue = mean_hue(&roi, &lit, &contour)?;
            let Some((colour, confidence)) = colour_bayes::classify(hue) else {
                continue;
            };
            let range = self.range(&shape);
            let rank = shape.score * confidence;
            if best.as_ref().is_none_or(|b| rank > b.0) {
                best = Some((
                    rank,
                    LightSeen {
                        colour,
                        range,
                        confidence,
                    },
                ));
            }
        }
        Ok(best.map(|b| b.1))
    }
}

impl LightFinder {
    /// Metres from the lens to a lamp seen as `shape`. Pinhole: a disc of radius R at depth
    /// Z spans r = f R / Z pixels (the contour runs through the rim pixels' centres, half a
    /// pixel inside the rim); the range is Z times the length of the ray of unit depth.
    fn range(&self, shape: &BlobShape) -> f64 {
        let k = &self.intrinsics;
        let depth = k.fx * self.lamp_radius / (shape.radius + 0.5);
        let (x, y) = (
            (shape.centre.0 - k.cx) / k.fx,
            (shape.centre.1 - k.cy) / k.fy,
        );
        depth * (1.0 + x * x + y * y).sqrt()
    }
}

/// The circular mean hue (OpenCV 0-180 units) of the lit pixels in `contour`'s box: red's
/// hues sit either side of 0/180, so they are averaged as angles (Mardia & Jupp 2.2.1).
fn mean_hue(hsv: &impl MatTraitConst, lit: &Mat, contour: &Vector<Point>) -> opencv::Result<f64> {
    let b = imgproc::bounding_rect(contour)?;
    let (mut s, mut c) = (0.0, 0.0);
    for y in b.y..b.y + b.height {
        for x in b.x..b.x + b.width {
            if *lit.at_2d::<u8>(y, x)? == 0 {
                continue;
            }
            let h = f64::from(hsv.at_2d::<core::Vec3b>(y, x)?[0]);
            let angle = h / 180.0 * std::f64::consts::TAU;
            s += angle.sin();
            c += angle.cos();
        }
    }
    Ok(s.atan2(c).rem_euclid(std::f64::consts::TAU) / std::f64::consts::TAU * 180.0)
}
