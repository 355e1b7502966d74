//! A block's centre from the lidar. The filter places a block from its two markers, and
//! a marker first seen from a metre away can be several centimetres off; the jaws forgive
//! 3.5 cm sideways. The lidar maps the block's faces to about a centimetre, so before the
//! final approach the block's centre is taken from a square of the block's size fitted to
//! the occupied cells around the estimate (navdeck's).

use crate::geometry::{Point2, Pose2};
use crate::map::costmap::Costmap;

/// Occupied cells this close belong to one object, metres (beam spacing at 1 m with 360
/// beams is 1.7 cm).
const LINK: f64 = 0.03;
/// Occupied cells needed to fit an outline.
const MIN_CELLS: usize = 4;
/// Orientations tried for the square, over its 90° symmetry.
const TURNS: usize = 30;

/// The centre of the block of side `size` the lidar mapped nearest `estimate` (within
/// `search` metres), seen from about `viewer`; `None` when no isolated object of a
/// block's size lies there.
pub fn lidar_centre(
    map: &Costmap,
    occupied: &[bool],
    estimate: Point2,
    size: f64,
    search: f64,
    viewer: Point2,
) -> Option<Point2> {
    if occupied.len() != map.width * map.height {
        return None;
    }
    let window = search + 2.0 * size;
    let (x0, x1) = map.columns_in(estimate.x - window, estimate.x + window)?;
    let (y0, y1) = map.rows_in(estimate.y - window, estimate.y + window)?;
    let mut points = Vec::new();
    for cy in y0..=y1 {
        for cx in x0..=x1 {
            if occupied[map.index(cx, cy)] {
                points.push(map.center_of(cx, cy));
            }
        }
    }
    outline_fit(&points, estimate, size, search, viewer, 0.0).map(|fit| fit.centre)
}

/// A lidar's range noise, metres (an LDS-01's and the twin's `[sim.lidar]` default): a
/// single scan's face is this rough.
const SCAN_RANGE_STD: f64 = 0.01;

/// The centre (world frame) of the block of side `size` that `scan` (hits in the frame of
/// a robot at `pose`) outlines nearest `estimate`, within `search` metres; `None` when no
/// isolated object of a block's size lies there. Relative to the robot it is as good as
/// the scan, whatever the error in `pose`.
pub fn scan_centre(
    scan: &[Point2],
    pose: Pose2,
    estimate: Point2,
    size: f64,
    search: f64,
) -> Option<Point2> {
    let near = pose.inverse_transform_point(estimate);
    let origin = Point2::new(0.0, 0.0);
    let fit = outline_fit(scan, near, size, search, origin, SCAN_RANGE_STD)?;
    Some(pose.transform_point(fit.centre))
}

/// A square of a block's size fitted to outline points: its centre, its turn (radians,
/// within a quarter turn: a square looks the same turned by one), and for each of its two
/// axes whether the points spanned it (two opposite ends seen) or only one face was.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SquareFit {
    pub centre: Point2,
    pub turn: f64,
    pub spanned: [bool; 2],
    /// How many points the outline had.
    pub points: usize,
}

/// The square of side `size` fitted to the object among `points` (outline points, e.g.
/// lidar returns) nearest `estimate` (within `search` metres), seen from about `viewer`;
/// `None` when no isolated object of a block's size lies there. `noise` is the points'
/// standard deviation (0 for map cells): noise alone spreads a face's points, so an axis
/// counts as spanned only when its extent beats that spread too.
pub fn outline_fit(
    points: &[Point2],
    estimate: Point2,
    size: f64,
    search: f64,
    viewer: Point2,
    noise: f64,
) -> Option<SquareFit> {
    let window = search + 2.0 * size;
    let points: Vec<Point2> = (points.iter())
        .filter(|p| (p.x - estimate.x).abs() <= window && (p.y - estimate.y).abs() <= window)
        .copied()
        .collect();
    let object = nearest_cluster(&points, estimate)?;
    let near_edge = |p: &Point2| {
        (p.x - estimate.x).abs() > window - LINK || (p.y - estimate.y).abs() > window - LINK
    };
    let span = object
        .iter()
        .flat_map(|a| object.iter().map(move |b| a.distance(*b)));
    let span = span.fold(0.0, f64::max);
    // Too big for a block, or too little of it mapped to say where its faces are.
    let outline = object.len() >= MIN_CELLS && span >= size / 2.0;
    if object.iter().any(near_edge) || span > 1.6 * size || !outline {
        return None;
    }
    let fit = fit_square(&object, size, viewer, noise);
    (fit.centre.distance(estimate) <= search).then_some(fit)
}

/// The points linked (chains of steps under `LINK`) to the point nearest `to`.
fn nearest_cluster(points: &[Point2], to: Point2) -> Option<Vec<Point2>> {
    let seed = (0..points.len())
        .min_by(|&a, &b| points[a].distance(to).total_cmp(&points[b].distance(to)))?;
    let mut member = vec![false; points.len()];
    member[seed] = true;
    let mut queue = vec![seed];
    while let Some(i) = queue.pop() {
        for j in 0..points.len() {
            if !member[j] && points[i].distance(points[j]) < LINK {
                member[j] = true;
                queue.push(j);
            }
        }
    }
    Some(
        (0..points.len())
            .filter(|&i| member[i])
            .map(|i| points[i])
            .collect(),
    )
}

/// The centre of the square of side `size` whose outline lies closest (least squares) to
/// `points`, tried at `TURNS` orientations, then at tenths of that step round the best.
/// Along an axis the points span, the centre is midway; along one they do not (one face
/// seen), it lies half a side behind that face, away from `viewer`. The points' own
/// spread is no span: an axis counts as spanned only when its extent also beats 4 `noise`
/// standard deviations (the range of up to 30 Gaussian samples stays under about 4:
/// tables of the range of a normal sample).
fn fit_square(points: &[Point2], size: f64, viewer: Point2, noise: f64) -> SquareFit {
    let step = std::f64::consts::FRAC_PI_2 / TURNS as f64;
    let better = |a: (f64, SquareFit), b: (f64, SquareFit)| if b.0 < a.0 { b } else { a };
    let at = |phi: f64| square_at(points, size, viewer, noise, phi);
    let coarse = (1..TURNS).fold(at(0.0), |best, k| better(best, at(k as f64 * step)));
    let around = coarse.1.turn;
    let fine = (-10..=10).fold(coarse, |best, k| {
        better(best, at(around + f64::from(k) * step / 10.0))
    });
    fine.1
}

/// The square turned `phi` that fits `points` best (see `fit_square`), and its score: the
/// sum of the squared distances from the points to its outline.
fn square_at(
    points: &[Point2],
    size: f64,
    viewer: Point2,
    noise: f64,
    phi: f64,
) -> (f64, SquareFit) {
    let half = size / 2.0;
    let (s, c) = phi.sin_cos();
    // Into the square's frame: u along its first side, v along the second.
    let local = |p: Point2| (c * p.x + s * p.y, -s * p.x + c * p.y);
    let uv: Vec<(f64, f64)> = points.iter().map(|&p| local(p)).collect();
    let eye = local(viewer);
    let centre_along = |coords: &[f64], eye: f64| {
        let (lo, hi) = coords
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
        if hi - lo >= (0.6 * size).max(4.0 * noise) {
            ((lo + hi) / 2.0, true)
        } else {
            let face = coords.iter().sum::<f64>() / coords.len() as f64;
            (if eye < face { face + half } else { face - half }, false)
        }
    };
    let us: Vec<f64> = uv.iter().map(|p| p.0).collect();
    let vs: Vec<f64> = uv.iter().map(|p| p.1).collect();
    let ((cu, spans_u), (cv, spans_v)) = (centre_along(&us, eye.0), centre_along(&vs, eye.1));
    // Distance from a point to the square's outline (inside or out).
    let score: f64 = uv
        .iter()
        .map(|&(u, v)| {
            let (du, dv) = ((u - cu).abs() - half, (v - cv).abs() - half);
            let outside = du.max(0.0).hypot(dv.max(0.0));
            let inside = du.max(dv).min(0.0);
            (outside + inside.abs()).powi(2)
        })
        .sum();
    let fit = SquareFit {
        centre: Point2::new(c * cu - s * cv, s * cu + c * cv),
        turn: phi,
        spanned: [spans_u, spans_v],
        points: points.len(),
    };
    (score, fit)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::costmap::FREE;

    /// 1 m x 1 m at 1 cm, with the outline cells of a 5 cm square at `centre`, turned
    /// `yaw`, on the faces `faces` (0: +x, 1: +y, 2: -x, 3: -y in the block's frame).
    fn block_map(centre: Point2, yaw: f64, faces: &[usize]) -> (Costmap, Vec<bool>) {
        let map = Costmap::new(100, 100, 0.01, Point2::new(0.0, 0.0), FREE);
        let mut occupied = vec![false; 100 * 100];
        let (s, c) = yaw.sin_cos();
        for &f in faces {
            for k in 0..=10 {
                let t = -0.025 + 0.005 * f64::from(k);
                let (u, v) = match f {
                    0 => (0.025, t),
                    1 => (t, 0.025),
                    2 => (-0.025, t),
                    _ => (t, -0.025),
                };
                let p = Point2::new(centre.x + c * u - s * v, centre.y + s * u + c * v);
                if let Some((x, y)) = map.cell_of(p) {
                    occupied[map.index(x, y)] = true;
                }
            }
        }
        (map, occupied)
    }

    #[test]
    fn two_faces_seen_give_the_centre_within_a_centimetre() {
        let truth = Point2::new(0.5, 0.5);
        for (yaw_deg, faces, viewer) in [
            (20.0f64, vec![0, 1], Point2::new(0.8, 0.7)),
            (-64.0, vec![0, 3], Point2::new(0.7, 0.2)),
            (0.0, vec![2, 3], Point2::new(0.2, 0.2)),
        ] {
            let (map, occupied) = block_map(truth, yaw_deg.to_radians(), &faces);
            // The markers put it 6 cm off.
            let estimate = Point2::new(0.54, 0.455);
            let got = lidar_centre(&map, &occupied, estimate, 0.05, 0.1, viewer).unwrap();
            assert!(got.distance(truth) < 0.01, "yaw {yaw_deg}: {got:?}");
        }
    }

    #[test]
    fn one_face_seen_puts_the_centre_half_a_side_behind_it() {
        let truth = Point2::new(0.5, 0.5);
        let (map, occupied) = block_map(truth, 0.0, &[2]);
        let got = lidar_centre(&map, &occupied, truth, 0.05, 0.1, Point2::new(0.2, 0.5));
        assert!(got.unwrap().distance(truth) < 0.01, "{got:?}");
    }

    #[test]
    fn a_cell_or_two_are_not_an_outline() {
        let map = Costmap::new(100, 100, 0.01, Point2::new(0.0, 0.0), FREE);
        let mut occupied = vec![false; 10_000];
        occupied[50 * 100 + 50] = true;
        let viewer = Point2::new(0.2, 0.2);
        let at = Point2::new(0.5, 0.5);
        assert!(lidar_centre(&map, &occupied, at, 0.05, 0.1, viewer).is_none());
        occupied[51 * 100 + 50] = true;
        assert!(lidar_centre(&map, &occupied, at, 0.05, 0.1, viewer).is_none());
    }

    #[test]
    fn nothing_a_wall_or_an_object_far_off_gives_no_centre() {
        let map = Costmap::new(100, 100, 0.01, Point2::new(0.0, 0.0), FREE);
        let viewer = Point2::new(0.2, 0.2);
        let at = Point2::new(0.5, 0.5);
        assert!(lidar_centre(&map, &vec![false; 10_000], at, 0.05, 0.1, viewer).is_none());
        let mut wall = vec![false; 10_000];
        for y in 0..100 {
            wall[y * 100 + 52] = true;
        }
        assert!(
            lidar_centre(&map, &wall, at, 0.05, 0.1, viewer).is_none(),
            "a wall"
        );
        let (map, occupied) = block_map(Point2::new(0.8, 0.8), 0.0, &[0, 1, 2, 3]);
        assert!(
            lidar_centre(&map, &occupied, at, 0.05, 0.1, viewer).is_none(),
            "too far"
        );
    }

    #[test]
    fn a_scan_places_the_block_relative_to_the_robot_whatever_the_pose_error() {
        // The block 0.25 m ahead, 3 cm left of the robot's axis; its near face seen.
        let here = Point2::new(0.25, 0.03);
        let scan: Vec<Point2> = (-5..=5)
            .map(|k| Point2::new(here.x - 0.025, here.y + 0.005 * f64::from(k)))
            .collect();
        // The filter believes the robot 16 cm and 2 degrees from where it is; the markers
        // put the block 6 cm off in that frame.
        let pose = Pose2::new(-1.9, -2.96, 0.035);
        let estimate = pose.transform_point(Point2::new(0.27, -0.02));
        let got = scan_centre(&scan, pose, estimate, 0.05, 0.1).unwrap();
        let seen = pose.inverse_transform_point(got);
        assert!(seen.distance(here) < 0.005, "{seen:?}");
        // Nothing outlined near the estimate: no centre.
        let far = pose.transform_point(Point2::new(0.6, 0.3));
        assert!(scan_centre(&scan, pose, far, 0.05, 0.1).is_none());
    }
}
