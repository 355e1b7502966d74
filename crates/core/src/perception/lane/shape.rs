//! Whether a bright blob is round like a lamp: seed 000 §3.1.3's geometric score, plus how
//! fully it fills its tightest box.

use opencv::core::{Point, Point2f, Vector};
use opencv::imgproc;

/// A blob's shape figures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlobShape {
    pub area: f64,
    /// seed 000 §3.1.3's validation score, 0-1.
    pub score: f64,
    /// Area over its tightest (rotated) box's.
    pub fill: f64,
    pub centre: (f64, f64),
    /// Radius of the enclosing circle, pixels.
    pub radius: f64,
    /// Major over minor axis of the fitted ellipse.
    pub aspect: f64,
}

/// The most a lamp's image is drawn out: seed 000 §3.1.3's 1.2 for a lamp seen face on,
/// times 1.25 for one seen off its axis near a corner of the picture (navdeck's figure:
/// 1 / cos 30 degrees off its axis, and the pinhole's stretch 30 degrees off the optical
/// axis, 1.15).
const OBLIQUE: f64 = 1.5;
/// The most a lamp the light finder reads may be drawn out: a lamp beside the lane seen
/// from a robot stopped close to it in a bend (1 / cos 60 degrees; the twin's frames show
/// 1.6 at a stop line). A drawn-out red stripe is told from such a lamp by its box
/// (`PASS_FILL`) and its surroundings (a lamp sits in a dark housing), not by this.
const OBLIQUE_ASIDE: f64 = 2.0;

/// seed 000 §3.1.3: a lamp scores over 0.7.
pub const PASS_SCORE: f64 = 0.7;
/// Not in the seed: the score alone passes a square (C = pi/4 = 0.785 >= 0.75, hull
/// compactness 1, aspect ratio 1: score 1.0), so a lamp must also leave the corners of its
/// tightest box empty: a disc, and a disc seen off its axis (an ellipse), fills pi/4 = 79 %
/// of it however drawn out, a square or any rectangle all of it. (The share of its enclosing
/// circle, which a square fills 64 %, cannot tell a square from a lamp seen 45 degrees off
/// its axis, which fills 71 % of it less a pixel's rim.)
pub const PASS_FILL: f64 = 0.9;

impl BlobShape {
    /// The figures of `contour`; none for a blob too small to measure.
    pub fn of(contour: &Vector<Point>) -> opencv::Result<Option<Self>> {
        let area = imgproc::contour_area_def(contour)?;
        let perimeter = imgproc::arc_length(contour, true)?;
        if area < 4.0 || perimeter <= 0.0 {
            return Ok(None);
        }
        // seed 000 §3.1.3: circularity C = 4 pi A / P^2.
        let circularity = 4.0 * std::f64::consts::PI * area / (perimeter * perimeter);
        let mut hull = Vector::<Point>::new();
        imgproc::convex_hull_def(contour, &mut hull)?;
        let hull_area = imgproc::contour_area_def(&hull)?;
        // seed 000 §3.1.3: compactness = A / A_convex.
        let compactness = if hull_area > 0.0 {
            area / hull_area
        } else {
            0.0
        };
        // seed 000 §3.1.3: AR = major / minor axis of the fitted ellipse (1 under 5 points).
        let aspect = if contour.len() >= 5 {
            let e = imgproc::fit_ellipse(contour)?;
            let (a, b) = (f64::from(e.size.width), f64::from(e.size.height));
            if a.min(b) > 0.0 {
                a.max(b) / a.min(b)
            } else {
                f64::INFINITY
            }
        } else {
            1.0
        };
        // seed 000 §3.1.3: 0.4 min(C / 0.75, 1) + 0.3 min(comp / 0.8, 1) + 0.3 [0.8 <= AR <= 1.2],
        // the band widened to OBLIQUE (a lamp beside the lane is seen off its axis).
        let score = 0.4 * (circularity / 0.75).min(1.0)
            + 0.3 * (compactness / 0.8).min(1.0)
            + 0.3 * f64::from(u8::from((1.0 / OBLIQUE..=OBLIQUE).contains(&aspect)));
        let mut centre = Point2f::default();
        let mut radius = 0.0f32;
        imgproc::min_enclosing_circle(contour, &mut centre, &mut radius)?;
        let radius = f64::from(radius);
        let rect = imgproc::min_area_rect(contour)?.size;
        let fill = area / (f64::from(rect.width) * f64::from(rect.height)).max(1e-9);
        Ok(Some(Self {
            area,
            score,
            fill,
            centre: (f64::from(centre.x), f64::from(centre.y)),
            radius,
            aspect,
        }))
    }

    /// Round enough to be a lamp.
    pub fn is_lamp(&self) -> bool {
        self.score > PASS_SCORE && self.fill <= PASS_FILL
    }

    /// Round enough to be a lamp seen from the side (`OBLIQUE_ASIDE`): the score's aspect
    /// band widened, the rest as `is_lamp`.
    pub fn is_lamp_aside(&self) -> bool {
        let widened = (OBLIQUE..=OBLIQUE_ASIDE).contains(&self.aspect)
            || (1.0 / OBLIQUE_ASIDE..=1.0 / OBLIQUE).contains(&self.aspect);
        let score = self.score + if widened { 0.3 } else { 0.0 };
        score > PASS_SCORE && self.fill <= PASS_FILL
    }
}
