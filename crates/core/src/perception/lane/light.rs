//! The lit lamp of a traffic light (seed 000 §3.1): bright saturated blobs above the
//! horizon, kept when round (§3.1.3), coloured by the Bayesian classifier (§3.1.2), ranged
//! from their size.

use super::birdseye::BirdsEye;
use super::colour_bayes;
use super::shape::BlobShape;
use crate::data::{LightColour, LightSeen};
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
    /// The camera, the lamp's radius in metres and each lamp's height, for the range.
    pub eye: BirdsEye,
    pub lamp_radius: f64,
    pub lamp_height: fn(LightColour) -> f64,
}

impl LightFinder {
    /// The nearest lit lamp in `hsv` (the whole frame in HSV), if any.
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
        let (cols, rows) = (roi.cols(), roi.rows());
        for contour in &contours {
            let Some(whole) = BlobShape::of(&contour)? else {
                continue;
            };
            let shape = if whole.is_lamp_aside() {
                whole
            } else {
                match cut_lamp(&contour, cols, rows, whole.area) {
                    Some(cut) => cut,
                    None => continue,
                }
            };
            if shape.area < MIN_AREA || !in_housing(&roi, &lit, &shape)? {
                continue;
            }
            let hue = mean_hue(&roi, &lit, &contour)?;
            let Some((colour, confidence)) = colour_bayes::classify(hue) else {
                continue;
            };
            let Some((range, ahead, left)) = self.range(&shape, colour) else {
                continue;
            };
            // The nearest lamp is the light ahead: a farther one (the next light down
            // the track, seen past this one) does not govern the robot yet.
            if best.as_ref().is_none_or(|b| range < b.0) {
                best = Some((
                    range,
                    LightSeen {
                        colour,
                        range,
                        ahead,
                        left,
                        confidence,
                    },
                ));
            }
        }
        Ok(best.map(|b| b.1))
    }
}

impl LightFinder {
    /// Metres from the lens to a lamp of `colour` seen as `shape`: where the ray through
    /// its centre meets that lamp's height (the lamp's row is sharper than its size, which
    /// a lamp seen off its axis or cut by the picture's edge shrinks). None when the ray
    /// never reaches that height ahead: a lamp above the lens is seen above the horizon,
    /// and a red blob below it (a barrier's stripe) is no lamp. A lamp below the lens is
    /// ranged by its size instead. Pinhole: a disc of radius R at depth Z spans
    /// r = f R / Z pixels (the contour runs through the rim pixels' centres, half a pixel
    /// inside the rim), and the lamp lies Z along the ray of unit depth. With the range,
    /// how far of it lies ahead along the robot's heading and how far left.
    fn range(&self, shape: &BlobShape, colour: LightColour) -> Option<(f64, f64, f64)> {
        let (u, v) = shape.centre;
        let mount = self.eye.mount();
        let lens = mount.to_robot(nalgebra::Vector3::zeros());
        let height = (self.lamp_height)(colour);
        let lamp = if height > lens.z {
            self.eye.meet_height(u, v, height)?
        } else {
            let k: &Intrinsics = self.eye.intrinsics();
            let depth = k.fx * self.lamp_radius / (shape.radius + 0.5);
            let ray = nalgebra::Vector3::new((u - k.cx) / k.fx, (v - k.cy) / k.fy, 1.0);
            lens + depth * mount.rotate_to_robot(ray)
        };
        Some(((lamp - lens).norm(), lamp.x - lens.x, lamp.y - lens.y))
    }
}

/// Least share of its disc a lamp cut by the picture's edge must show.
const CUT_VISIBLE: f64 = 0.3;
/// Most RMS distance of a cut lamp's rim from its fitted circle, as a share of its radius.
const CUT_ROUNDNESS: f64 = 0.05;
/// Least radius, pixels, and rim points off the edge of a cut lamp: a smaller blob's
/// outline is too coarse to tell a disc from the end of a barrier's stripe.
const CUT_RADIUS_PX: f64 = 6.0;
const CUT_RIM_POINTS: usize = 16;
/// Least arc of its rim, degrees, a cut lamp must show.
const CUT_ARC_DEG: f64 = 150.0;

/// A lamp cut by the picture's edge (a light beside the lane in a bend): its rim off the
/// edge must lie on a circle (Kasa's algebraic fit, Kasa 1976), and the blob must fill
/// the part of that circle inside the picture; none otherwise.
fn cut_lamp(contour: &Vector<Point>, cols: i32, rows: i32, area: f64) -> Option<BlobShape> {
    let on_edge = |p: &Point| p.x <= 0 || p.y <= 0 || p.x >= cols - 1 || p.y >= rows - 1;
    if !contour.iter().any(|p| on_edge(&p)) {
        return None;
    }
    let rim: Vec<(f64, f64)> = (contour.iter())
        .filter(|p| !on_edge(p))
        .map(|p| (f64::from(p.x), f64::from(p.y)))
        .collect();
    if rim.len() < CUT_RIM_POINTS {
        return None;
    }
    // x^2 + y^2 + D x + E y + F = 0 by least squares: centre (-D/2, -E/2).
    let mut normal = nalgebra::Matrix3::<f64>::zeros();
    let mut rhs = nalgebra::Vector3::<f64>::zeros();
    for &(x, y) in &rim {
        let row = nalgebra::Vector3::new(x, y, 1.0);
        normal += row * row.transpose();
        rhs -= (x * x + y * y) * row;
    }
    let p = normal.lu().solve(&rhs)?;
    let centre = (-p[0] / 2.0, -p[1] / 2.0);
    let radius = (centre.0 * centre.0 + centre.1 * centre.1 - p[2]).sqrt();
    if !radius.is_finite() || !(CUT_RADIUS_PX..=80.0).contains(&radius) {
        return None;
    }
    let miss = rim
        .iter()
        .map(|&(x, y)| ((x - centre.0).hypot(y - centre.1) - radius).powi(2))
        .sum::<f64>()
        / rim.len() as f64;
    let visible = area / (std::f64::consts::PI * radius * radius);
    // The rim's angular span about the centre: its bearings sorted, less the widest gap.
    let mut bearings: Vec<f64> = (rim.iter())
        .map(|&(x, y)| (y - centre.1).atan2(x - centre.0).to_degrees())
        .collect();
    bearings.sort_by(f64::total_cmp);
    let wrap = 360.0 - (bearings[bearings.len() - 1] - bearings[0]);
    let widest = (bearings.windows(2))
        .map(|w| w[1] - w[0])
        .fold(wrap, f64::max);
    if 360.0 - widest < CUT_ARC_DEG {
        return None;
    }
    (miss.sqrt() <= CUT_ROUNDNESS * radius && (CUT_VISIBLE..=1.1).contains(&visible)).then_some(
        BlobShape {
            area,
            score: super::shape::PASS_SCORE,
            // A disc's share of its box: the cut disc was checked round above.
            fill: std::f64::consts::FRAC_PI_4,
            aspect: 1.0,
            centre,
            radius,
        },
    )
}

/// Least share of the unlit pixels just around a lamp that are dark (a quarter: a lamp seen
/// from the side of a bend shows the wall past its housing's thin rim): a lamp sits in its
/// housing (and beside its unlit neighbours), where the red end of a barrier's arm lies
/// between white stripes and the wall behind.
const HOUSING_DARK_SHARE: f64 = 0.25;
/// Around a lamp a pixel is dark under this share of the lamp's own mean brightness: the
/// lamp glows whatever the room's light, its housing does not.
const HOUSING_DARK: f64 = 0.4;

/// Whether the unlit pixels within a quarter radius (at least 2) of `shape`'s rim are
/// mostly dark, as a traffic light's housing is.
fn in_housing(hsv: &impl MatTraitConst, lit: &Mat, shape: &BlobShape) -> opencv::Result<bool> {
    let ((cx, cy), r) = (shape.centre, shape.radius);
    let outer = r + (0.25 * r).max(2.0);
    let (cols, rows) = (hsv.cols(), hsv.rows());
    let (x0, x1) = (
        (cx - outer).floor().max(0.0) as i32,
        (cx + outer).ceil() as i32,
    );
    let (y0, y1) = (
        (cy - outer).floor().max(0.0) as i32,
        (cy + outer).ceil() as i32,
    );
    let (mut glow, mut lamp) = (0.0, 0usize);
    let mut ring = Vec::new();
    for y in y0..y1.min(rows) {
        for x in x0..x1.min(cols) {
            let d = (f64::from(x) - cx).hypot(f64::from(y) - cy);
            if d > outer {
                continue;
            }
            let v = f64::from(hsv.at_2d::<core::Vec3b>(y, x)?[2]);
            if *lit.at_2d::<u8>(y, x)? != 0 {
                if d <= r {
                    glow += v;
                    lamp += 1;
                }
            } else if d > r {
                ring.push(v);
            }
        }
    }
    if lamp == 0 || ring.is_empty() {
        return Ok(false);
    }
    let dark = HOUSING_DARK * glow / lamp as f64;
    let share = ring.iter().filter(|&&v| v < dark).count() as f64 / ring.len() as f64;
    Ok(share >= HOUSING_DARK_SHARE)
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
