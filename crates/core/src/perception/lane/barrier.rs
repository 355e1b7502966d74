//! The barrier's arm in one frame (seed 000 §3.2): its red stripes, their edges' Hough
//! segments (§3.2.1's adaptive lengths, every direction kept: a raised arm is upright) and
//! each stripe's long axis, clustered and the biggest cluster's principal axis taken
//! (§3.2.2), refined over the red pixels along it; then the arm's angle and range from the
//! camera geometry.
//!
//! An arm turning in an upright plane across the lane, seen from a camera above and beside
//! its pivot, does not show its true angle in the image. Its lowest end is its pivot at
//! `ARM_HEIGHT`, so the ray through that end fixes how far ahead the arm's plane is (or,
//! when that ray does not come down to the pivot's height, the arm's thickness in the image
//! does); both ends' rays are then met with that plane, taken square to the robot's
//! heading as it is when the robot follows the lane, and the angle measured there.

use super::arm_axis::{Axis, Segment, arm_axis};
use super::birdseye::BirdsEye;
use super::shape::BlobShape;
use crate::data::BarrierState;
use nalgebra::Vector3;
use opencv::core::{self, Mat, Point, Point2f, Scalar, Vec4i, Vector};
use opencv::imgproc;
use opencv::prelude::*;

/// The arm as one frame shows it, before any filtering.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BarrierObservation {
    /// seed 000 §3.2.3's band of `angle_deg`.
    pub state: BarrierState,
    /// The arm's angle above level in its own plane, degrees.
    pub angle_deg: f64,
    /// The angle of the arm's image, degrees above the image rows.
    pub image_angle_deg: f64,
    /// Metres ahead of the camera to the arm's plane.
    pub range: f64,
    /// 0.5-0.95: how much of the red edges the arm's cluster holds.
    pub confidence: f64,
}

/// Red stripes: hue within 10 of 0/180 (seed 000 §3.1.1's red peaks, 10 and 170), vivid.
const RED_SATURATION: f64 = 100.0;
const RED_VALUE: f64 = 60.0;
/// Hough votes for a segment (the seed's adaptive threshold is not given).
const VOTES: i32 = 20;
/// Least ratio of an arm's length to its thickness in the image.
const ARM_SLENDER: f64 = 3.0;
/// Least area of a red blob taken as a stripe, pixels.
const MIN_STRIPE_AREA: f64 = 30.0;

/// Finds the arm with one camera's geometry.
pub struct ArmFinder {
    pub eye: BirdsEye,
    /// The arm's pivot height, metres.
    pub arm_height: f64,
    /// The arm's thickness, metres (the range when the pivot cannot be placed).
    pub arm_thickness: f64,
}

impl ArmFinder {
    /// The arm in `hsv` (the whole frame in HSV), if one is seen.
    pub fn find(&self, hsv: &Mat) -> opencv::Result<Option<BarrierObservation>> {
        let (red, stripe_axes) = self.stripes(hsv)?;
        // Edges lie only round red pixels: the edge and Hough passes look only at the
        // box round them (and not at all when there are none).
        let found = imgproc::bounding_rect(&red)?;
        if found.width == 0 || found.height == 0 {
            return Ok(None);
        }
        let margin = 4;
        let (x0, y0) = ((found.x - margin).max(0), (found.y - margin).max(0));
        let x1 = (found.x + found.width + margin).min(red.cols());
        let y1 = (found.y + found.height + margin).min(red.rows());
        let near_red = Mat::roi(&red, core::Rect::new(x0, y0, x1 - x0, y1 - y0))?;
        let mut edges = Mat::default();
        imgproc::canny_def(&near_red, &mut edges, 50.0, 150.0)?;
        let side = f64::from(hsv.rows().min(hsv.cols()));
        // seed 000 §3.2.1: minLineLength = max(30, 0.05 min side), maxLineGap = max(10, 0.02 min side).
        let (min_length, max_gap) = (
            (0.05 * side).floor().max(30.0),
            (0.02 * side).floor().max(10.0),
        );
        let mut lines = Vector::<Vec4i>::new();
        // rho 1 px, theta 1 degree (seed 000 §3.2.1).
        imgproc::hough_lines_p(
            &edges,
            &mut lines,
            1.0,
            std::f64::consts::PI / 180.0,
            VOTES,
            min_length,
            max_gap,
        )?;
        // The Hough segments of the stripes' edges, and each stripe's own long axis (the
        // seed's red objects, §3.2.2): a stripe's edges can be too short for the Hough
        // transform's least length when the arm is far or slanted.
        let offset = [x0, y0, x0, y0].map(f64::from);
        let segments: Vec<Segment> = lines
            .iter()
            .map(|l| [0, 1, 2, 3].map(|i| f64::from(l[i]) + offset[i]))
            .chain(stripe_axes)
            .collect();
        // Linked within a little more than the arm is thick up close (0.03 m at 0.4 m).
        let Some(axis) = arm_axis(&segments, (0.0625 * side).max(20.0)) else {
            return Ok(None);
        };
        let Some(band) = band_along(&red, &axis)? else {
            return Ok(None);
        };
        let [a, b] = band.ends;
        // An arm is longer than the least Hough segment twice over; a lone red scrap is not.
        let length = (b.0 - a.0).hypot(b.1 - a.1);
        if length < 2.0 * min_length {
            return Ok(None);
        }
        // An arm is slender (0.03 m thick, half a metre long); a box's red face is not.
        if length < ARM_SLENDER * band.thickness_px {
            return Ok(None);
        }
        let image_angle_deg = (a.1 - b.1).abs().atan2((a.0 - b.0).abs()).to_degrees();
        let Some(ahead) = self
            .pivot_ahead(a, b)
            .or_else(|| self.thickness_ahead(&band))
        else {
            return Ok(None);
        };
        let Some(angle_deg) = self.angle_in_plane(a, b, ahead) else {
            return Ok(None);
        };
        let lens = self.eye.mount().to_robot(Vector3::zeros());
        Ok(Some(BarrierObservation {
            state: BarrierState::of_angle(angle_deg),
            angle_deg,
            image_angle_deg,
            range: ahead - lens.x,
            // seed 000 §3.2.2: confidence = the cluster's share of the points, here of the
            // segment length, mapped to 0.5-0.95 so one frame never makes the filter sure.
            confidence: 0.5 + 0.45 * axis.share,
        }))
    }

    /// The red mask with lamp-like (round) blobs taken out (the arm's stripes are bars),
    /// and the long axis of each elongated red blob.
    fn stripes(&self, hsv: &Mat) -> opencv::Result<(Mat, Vec<Segment>)> {
        let (mut low, mut high, mut red) = (Mat::default(), Mat::default(), Mat::default());
        core::in_range(
            hsv,
            &Scalar::new(0.0, RED_SATURATION, RED_VALUE, 0.0),
            &Scalar::new(10.0, 255.0, 255.0, 0.0),
            &mut low,
        )?;
        core::in_range(
            hsv,
            &Scalar::new(170.0, RED_SATURATION, RED_VALUE, 0.0),
            &Scalar::new(180.0, 255.0, 255.0, 0.0),
            &mut high,
        )?;
        core::bitwise_or_def(&low, &high, &mut red)?;
        let mut contours = Vector::<Vector<Point>>::new();
        imgproc::find_contours_def(
            &red,
            &mut contours,
            imgproc::RETR_EXTERNAL,
            imgproc::CHAIN_APPROX_NONE,
        )?;
        let mut axes = Vec::new();
        for (i, contour) in contours.iter().enumerate() {
            match BlobShape::of(&contour)? {
                Some(shape) if shape.is_lamp() => {
                    imgproc::draw_contours(
                        &mut red,
                        &contours,
                        i as i32,
                        Scalar::all(0.0),
                        imgproc::FILLED,
                        imgproc::LINE_8,
                        &core::no_array(),
                        0,
                        Point::default(),
                    )?;
                }
                Some(shape) if shape.area >= MIN_STRIPE_AREA => axes.extend(long_axis(&contour)?),
                _ => {}
            }
        }
        Ok((red, axes))
    }

    /// How far ahead the arm's plane is, from its lower end (the pivot, at `arm_height`).
    fn pivot_ahead(&self, a: (f64, f64), b: (f64, f64)) -> Option<f64> {
        let low = if a.1 >= b.1 { a } else { b };
        let ahead = self.eye.meet_height(low.0, low.1, self.arm_height)?.x;
        let lens = self.eye.mount().to_robot(Vector3::zeros());
        (ahead - lens.x > 0.02 && ahead - lens.x < 5.0).then_some(ahead)
    }

    /// How far ahead the arm's plane is, from its thickness in the image: depth along the
    /// optical axis Z = f t / t_px (pinhole), then along the ray through the band's middle.
    fn thickness_ahead(&self, band: &Band) -> Option<f64> {
        if band.thickness_px < 2.0 {
            return None;
        }
        let depth = self.eye.intrinsics().fx * self.arm_thickness / band.thickness_px;
        let [a, b] = band.ends;
        let (o, d) = self.eye.ray((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0);
        // `ray` gives a direction of unit depth, so `depth` along it is the point.
        Some((o + depth * d).x)
    }

    /// The arm's angle above level in the upright plane `x = ahead`: both ends' rays met
    /// with the plane, then atan2(rise, run across).
    fn angle_in_plane(&self, a: (f64, f64), b: (f64, f64), ahead: f64) -> Option<f64> {
        let p = self.eye.meet_ahead(a.0, a.1, ahead)?;
        let q = self.eye.meet_ahead(b.0, b.1, ahead)?;
        Some((q.z - p.z).abs().atan2((q.y - p.y).abs()).to_degrees())
    }
}

/// The red pixels along an axis: their extent along it and the band's thickness.
struct Band {
    ends: [(f64, f64); 2],
    thickness_px: f64,
}

/// Red pixels of `red` within reach of the Hough axis (its edges lie half a thickness
/// either side, so 1.5 spreads and 4 px), their own principal axis taken twice over so
/// stripes whose edges were too short for the Hough transform count too: the band's ends
/// along it and its thickness from the spread across it (a uniform band of width w has
/// standard deviation w / sqrt 12).
fn band_along(red: &Mat, axis: &Axis) -> opencv::Result<Option<Band>> {
    let mut found = Vector::<Point>::new();
    core::find_non_zero(red, &mut found)?;
    let pixels: Vec<(f64, f64)> = found
        .iter()
        .map(|p| (f64::from(p.x), f64::from(p.y)))
        .collect();
    let [a, b] = axis.ends;
    let length = (b.0 - a.0).hypot(b.1 - a.1);
    if length < 1.0 {
        return Ok(None);
    }
    let mut line = (a, ((b.0 - a.0) / length, (b.1 - a.1) / length));
    let mut reach = 1.5 * axis.spread + 4.0;
    let mut band = None;
    for _ in 0..3 {
        let (origin, dir) = line;
        let near: Vec<(f64, f64)> = pixels
            .iter()
            .copied()
            .filter(|p| ((p.0 - origin.0) * -dir.1 + (p.1 - origin.1) * dir.0).abs() <= reach)
            .collect();
        let Some(pca) = principal_axis(&near) else {
            return Ok(band);
        };
        let along =
            |p: &(f64, f64)| (p.0 - pca.mean.0) * pca.dir.0 + (p.1 - pca.mean.1) * pca.dir.1;
        let lo = near.iter().map(along).fold(f64::INFINITY, f64::min);
        let hi = near.iter().map(along).fold(f64::NEG_INFINITY, f64::max);
        let at = |t: f64| (pca.mean.0 + t * pca.dir.0, pca.mean.1 + t * pca.dir.1);
        let thickness_px = (12.0 * pca.minor).sqrt();
        band = Some(Band {
            ends: [at(lo), at(hi)],
            thickness_px,
        });
        line = (pca.mean, pca.dir);
        reach = 0.5 * thickness_px + 4.0;
    }
    Ok(band)
}

/// The long axis of a blob's least-area rectangle, when it is at least 1.5 times as long
/// as it is wide (Freeman & Shapira's minimum-area enclosing rectangle, as OpenCV finds it).
fn long_axis(contour: &Vector<Point>) -> opencv::Result<Option<Segment>> {
    let rect = imgproc::min_area_rect(contour)?;
    let mut c = [Point2f::default(); 4];
    rect.points(&mut c)?;
    let mid = |a: Point2f, b: Point2f| ((f64::from(a.x + b.x)) / 2.0, (f64::from(a.y + b.y)) / 2.0);
    let side = |a: Point2f, b: Point2f| f64::from((a.x - b.x).hypot(a.y - b.y));
    let (first, second) = (side(c[0], c[1]), side(c[1], c[2]));
    if first.max(second) < 1.5 * first.min(second) {
        return Ok(None);
    }
    // The axis joins the middles of the two short sides.
    let (p, q) = if first >= second {
        (mid(c[1], c[2]), mid(c[3], c[0]))
    } else {
        (mid(c[0], c[1]), mid(c[2], c[3]))
    };
    Ok(Some([p.0, p.1, q.0, q.1]))
}

/// Mean, principal direction and variance across it of a point set.
struct Principal {
    mean: (f64, f64),
    dir: (f64, f64),
    minor: f64,
}

/// The principal axis of `points`: theta = atan2(2 sxy, sxx - syy) / 2 and the smaller
/// eigenvalue of the 2x2 covariance (Jolliffe, Principal Component Analysis, 1.1).
fn principal_axis(points: &[(f64, f64)]) -> Option<Principal> {
    if points.len() < 2 {
        return None;
    }
    let n = points.len() as f64;
    let mean = points
        .iter()
        .fold((0.0, 0.0), |m, p| (m.0 + p.0 / n, m.1 + p.1 / n));
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for p in points {
        let (dx, dy) = (p.0 - mean.0, p.1 - mean.1);
        sxx += dx * dx / n;
        sxy += dx * dy / n;
        syy += dy * dy / n;
    }
    let theta = 0.5 * (2.0 * sxy).atan2(sxx - syy);
    let half = ((sxx - syy) / 2.0).hypot(sxy);
    Some(Principal {
        mean,
        dir: (theta.cos(), theta.sin()),
        minor: ((sxx + syy) / 2.0 - half).max(0.0),
    })
}
