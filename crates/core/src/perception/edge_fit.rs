//! Marker corners from the marker's four edges: each edge of the black square is located
//! to a fraction of a pixel at many points along it, a straight line is fitted through
//! them, and neighbouring lines meet at the corners.
//!
//! A corner found from the few pixels around it (OpenCV's `cornerSubPix`) sits about
//! 0.2 px inside the square, which for a 20 px marker is a 2 % range error. An edge holds
//! many more pixels, and where it lies can be measured without bias: across a step edge
//! blurred by any symmetric spread (a pixel's area, a lens), the dark area on the light
//! side of the edge equals the light area on the dark side, so
//! `edge = s0 + integral(s0..s1) (light - I(s)) ds / (light - dark)`.
//! (The same moment idea as Tabatabai & Mitchell, "Edge location to subpixel values",
//! IEEE PAMI 1984.)

use super::frame::GrayFrame;

/// Cells across an ArUco original marker's black square.
const CELLS: f64 = 7.0;
/// Least step along an edge and the step across it, pixels.
const ALONG_STEP: f64 = 0.5;
const ACROSS_STEP: f64 = 0.5;
/// Least light-dark difference, grey levels, for an edge to be measured.
const MIN_CONTRAST: f64 = 12.0;
/// Least points on an edge for a line to be fitted.
const MIN_POINTS: usize = 4;
/// Most points measured on one edge: more add time, not accuracy (the line through 48
/// points with 0.2 px of scatter each is placed to 0.03 px).
const MAX_POINTS: f64 = 48.0;

type Xy = [f64; 2];

/// What the edges of one marker showed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Refined {
    /// The corners, clockwise from the top-left as the detector gave them, moved onto
    /// the crossings of the fitted edge lines.
    Corners([[f32; 2]; 4]),
    /// An edge has no white margin outside it, as the others do: something in front
    /// hides part of the marker, and the square found is not the whole marker.
    Hidden,
    /// An edge could not be measured (too small, too little contrast, partly outside
    /// the frame) or a corner would move further than a cell: keep the corners as found.
    Unmeasured,
}

/// Refines the corners of one marker of `frame` (see [`Refined`]).
pub fn refine(frame: &GrayFrame, corners: [[f32; 2]; 4]) -> Refined {
    let start: [Xy; 4] = corners.map(|[x, y]| [f64::from(x), f64::from(y)]);
    let cell = shortest_side(&corners) / CELLS;
    if cell < 1.5 {
        return Refined::Unmeasured;
    }
    let levels = match Levels::measure(frame, &start) {
        Some(Ok(levels)) => levels,
        Some(Err(Hidden)) => return Refined::Hidden,
        None => return Refined::Unmeasured,
    };
    refine_lines(frame, start, &levels)
        .filter(|found| (0..4).all(|i| dist(found[i], start[i]) <= cell.min(2.0)))
        .map_or(Refined::Unmeasured, |found| {
            Refined::Corners(found.map(|[x, y]| [x as f32, y as f32]))
        })
}

/// Corners from edge lines fitted twice: the second pass samples along lines the first
/// has already straightened.
fn refine_lines(frame: &GrayFrame, mut quad: [Xy; 4], levels: &Levels) -> Option<[Xy; 4]> {
    for _ in 0..2 {
        let lines: Vec<Line> = (0..4)
            .map(|i| fit_edge(frame, &quad, i, levels))
            .collect::<Option<_>>()?;
        let mut next = quad;
        for (i, corner) in next.iter_mut().enumerate() {
            *corner = lines[(i + 3) % 4].meet(&lines[i])?;
        }
        quad = next;
    }
    Some(quad)
}

/// An edge of the marker without its white margin.
struct Hidden;

/// Grey levels of the black border and of the white margin round it, in this frame.
struct Levels {
    dark: f64,
    light: f64,
}

impl Levels {
    /// Medians over every edge: half a cell inside (the border's middle) and one cell
    /// outside (inside the quiet zone). `None` when a sample falls outside the frame or
    /// the contrast is too low. `Hidden` when one edge does not run between the black
    /// border and the white margin as the others do: its inside or its outside is more
    /// than a quarter of the contrast away from the darkest inside and whitest outside
    /// (something in front covers that side of the marker).
    fn measure(frame: &GrayFrame, quad: &[Xy; 4]) -> Option<Result<Self, Hidden>> {
        let mut dark = Vec::new();
        let mut light = Vec::new();
        let mut per_edge = [(0.0, 0.0); 4];
        for (i, levels) in per_edge.iter_mut().enumerate() {
            let (mut inside, mut outside) = (Vec::new(), Vec::new());
            let cell = cell_across(quad, i);
            for (p, n) in edge_samples(quad, i) {
                inside.push(frame.sample(p[0] - 0.5 * cell * n[0], p[1] - 0.5 * cell * n[1])?);
                outside.push(frame.sample(p[0] + cell * n[0], p[1] + cell * n[1])?);
            }
            dark.extend_from_slice(&inside);
            light.extend_from_slice(&outside);
            *levels = (median(&mut inside)?, median(&mut outside)?);
        }
        let levels = Self {
            dark: median(&mut dark)?,
            light: median(&mut light)?,
        };
        if levels.light - levels.dark < MIN_CONTRAST {
            return None;
        }
        let darkest = per_edge.iter().map(|e| e.0).fold(f64::INFINITY, f64::min);
        let whitest = per_edge
            .iter()
            .map(|e| e.1)
            .fold(f64::NEG_INFINITY, f64::max);
        let slack = 0.25 * (whitest - darkest);
        let clean = per_edge
            .iter()
            .all(|&(inside, outside)| inside <= darkest + slack && outside >= whitest - slack);
        Some(if clean { Ok(levels) } else { Err(Hidden) })
    }
}

/// Points along edge `i` (corner `i` to corner `i + 1`) with the outward normal there,
/// leaving out a cell at each end where the neighbouring edge's blur reaches: every half
/// pixel, or `MAX_POINTS` evenly spread on a long edge.
fn edge_samples(quad: &[Xy; 4], i: usize) -> impl Iterator<Item = (Xy, Xy)> {
    let (a, b) = (quad[i], quad[(i + 1) % 4]);
    let len = dist(a, b);
    let u = [(b[0] - a[0]) / len, (b[1] - a[1]) / len];
    // Corners run clockwise on screen (y down), so the outward normal is u turned left.
    let n = [u[1], -u[0]];
    let first = (len / CELLS).max(1.5);
    let span = len - 2.0 * first;
    let step = ALONG_STEP.max(span / MAX_POINTS);
    let count = (span / step).floor().max(-1.0) as i64 + 1;
    (0..count).map(move |k| {
        let t = first + k as f64 * step;
        ([a[0] + t * u[0], a[1] + t * u[1]], n)
    })
}

/// The line through edge `i` of `quad`, from its measured points.
fn fit_edge(frame: &GrayFrame, quad: &[Xy; 4], i: usize, levels: &Levels) -> Option<Line> {
    let cell = cell_across(quad, i);
    // From the border's middle to a cell out: wide enough for the blur, clear of the
    // data cells inside the border.
    let (s0, s1) = (-(0.5 * cell).min(3.0), cell.min(4.0));
    let steps = ((s1 - s0) / ACROSS_STEP).round() as usize;
    let contrast = levels.light - levels.dark;
    let points: Vec<Xy> = edge_samples(quad, i)
        .filter_map(|(p, n)| {
            // Trapezoidal integral of the light deficit across the edge.
            let mut deficit = 0.0;
            for k in 0..=steps {
                let s = s0 + k as f64 * ACROSS_STEP;
                let g = frame.sample(p[0] + s * n[0], p[1] + s * n[1])?;
                let w = if k == 0 || k == steps { 0.5 } else { 1.0 };
                deficit += w * (levels.light - g).clamp(0.0, contrast);
            }
            let s = s0 + deficit * ACROSS_STEP / contrast;
            Some([p[0] + s * n[0], p[1] + s * n[1]])
        })
        .collect();
    Line::fit(&points)
}

/// A cell's width across edge `i`: the mean of the two edges beside it over 7 cells
/// (a marker seen obliquely has narrow cells one way and wide ones the other).
fn cell_across(quad: &[Xy; 4], i: usize) -> f64 {
    let before = dist(quad[(i + 3) % 4], quad[i]);
    let after = dist(quad[(i + 1) % 4], quad[(i + 2) % 4]);
    (before + after) / 2.0 / CELLS
}

/// A line through `point` along the unit vector `dir`.
#[derive(Clone, Copy, Debug)]
struct Line {
    point: Xy,
    dir: Xy,
}

impl Line {
    /// Total least squares: through the centroid along the covariance's major axis.
    fn fit(points: &[Xy]) -> Option<Self> {
        if points.len() < MIN_POINTS {
            return None;
        }
        let n = points.len() as f64;
        let mx = points.iter().map(|p| p[0]).sum::<f64>() / n;
        let my = points.iter().map(|p| p[1]).sum::<f64>() / n;
        let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
        for p in points {
            let (dx, dy) = (p[0] - mx, p[1] - my);
            sxx += dx * dx;
            sxy += dx * dy;
            syy += dy * dy;
        }
        // Major axis angle of a 2x2 covariance: 0.5 atan2(2 sxy, sxx - syy).
        let angle = 0.5 * (2.0 * sxy).atan2(sxx - syy);
        Some(Self {
            point: [mx, my],
            dir: [angle.cos(), angle.sin()],
        })
    }

    /// Where two lines cross (Cramer's rule), if they are not nearly parallel.
    fn meet(&self, other: &Line) -> Option<Xy> {
        let det = self.dir[0] * other.dir[1] - self.dir[1] * other.dir[0];
        if det.abs() < 0.1 {
            return None;
        }
        let (dx, dy) = (
            other.point[0] - self.point[0],
            other.point[1] - self.point[1],
        );
        let t = (dx * other.dir[1] - dy * other.dir[0]) / det;
        Some([
            self.point[0] + t * self.dir[0],
            self.point[1] + t * self.dir[1],
        ])
    }
}

/// The shortest side of a marker's quad in the image, pixels.
pub fn shortest_side(corners: &[[f32; 2]; 4]) -> f64 {
    let at = |k: usize| [f64::from(corners[k][0]), f64::from(corners[k][1])];
    (0..4)
        .map(|k| dist(at(k), at((k + 1) % 4)))
        .fold(f64::INFINITY, f64::min)
}

fn dist(a: Xy, b: Xy) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// The middle value (the upper one of an even count), sorting `values`; `None` if empty.
pub(super) fn median(values: &mut [f64]) -> Option<f64> {
    if values.is_empty() {
        return None;
    }
    values.sort_by(f64::total_cmp);
    Some(values[values.len() / 2])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A frame of `w` x `h` with a dark square of corners `quad`, each pixel the mean of
    /// 16 x 16 sub-samples (the pixel's area), dark 40 on light 200.
    fn square(w: usize, h: usize, quad: [Xy; 4]) -> GrayFrame {
        let inside = |x: f64, y: f64| {
            (0..4).all(|i| {
                let (a, b) = (quad[i], quad[(i + 1) % 4]);
                // Clockwise on screen: inside is to the right of each edge.
                (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]) >= 0.0
            })
        };
        let mut data = vec![0u8; w * h];
        for y in 0..h {
            for x in 0..w {
                let mut dark = 0;
                for j in 0..16 {
                    for i in 0..16 {
                        let sx = x as f64 - 0.5 + (i as f64 + 0.5) / 16.0;
                        let sy = y as f64 - 0.5 + (j as f64 + 0.5) / 16.0;
                        dark += usize::from(inside(sx, sy));
                    }
                }
                data[y * w + x] = (200.0 - 160.0 * dark as f64 / 256.0).round() as u8;
            }
        }
        GrayFrame {
            width: w,
            height: h,
            data,
        }
    }

    #[test]
    fn corners_of_a_small_tilted_square_are_found_to_a_twentieth_of_a_pixel() {
        // An 18 px square turned 20 degrees, its corners off the pixel grid.
        let (cx, cy, half, turn) = (30.3, 29.7, 9.0, 20f64.to_radians());
        let (s, c) = turn.sin_cos();
        let truth: [Xy; 4] = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
            .map(|(a, b)| [cx + half * (a * c - b * s), cy + half * (a * s + b * c)]);
        let frame = square(60, 60, truth);
        // Start from corners 0.4 px inside, as a corner detector leaves them.
        let start = truth.map(|p| {
            let (dx, dy) = (cx - p[0], cy - p[1]);
            let k = 0.4 / dx.hypot(dy);
            [(p[0] + k * dx) as f32, (p[1] + k * dy) as f32]
        });
        assert_refined_to(&frame, start, truth, 0.05);
    }

    #[test]
    fn an_axis_aligned_square_has_no_half_pixel_bias() {
        let truth: [Xy; 4] = [
            [10.25, 10.25],
            [30.25, 10.25],
            [30.25, 30.25],
            [10.25, 30.25],
        ];
        let frame = square(42, 42, truth);
        let start = truth.map(|[x, y]| [x as f32, y as f32]);
        assert_refined_to(&frame, start, truth, 0.02);
    }

    /// Refining `start` in `frame` puts every corner within `tolerance` px of `truth`.
    fn assert_refined_to(frame: &GrayFrame, start: [[f32; 2]; 4], truth: [Xy; 4], tolerance: f64) {
        let Refined::Corners(found) = refine(frame, start) else {
            panic!("not refined")
        };
        for (f, t) in found.iter().zip(truth) {
            let error = dist([f64::from(f[0]), f64::from(f[1])], t);
            assert!(error < tolerance, "corner {f:?} vs {t:?}: {error:.3} px");
        }
    }

    #[test]
    fn a_square_cut_by_the_frame_edge_or_without_contrast_is_left_alone() {
        let cut: [Xy; 4] = [[-5.0, 5.0], [15.0, 5.0], [15.0, 25.0], [-5.0, 25.0]];
        let frame = square(30, 30, cut);
        assert_eq!(
            refine(&frame, cut.map(|[x, y]| [x as f32, y as f32])),
            Refined::Unmeasured
        );
        let flat = GrayFrame {
            width: 30,
            height: 30,
            data: vec![128; 900],
        };
        let quad = [[5.0, 5.0], [25.0, 5.0], [25.0, 25.0], [5.0, 25.0]];
        assert_eq!(refine(&flat, quad), Refined::Unmeasured);
    }

    #[test]
    fn a_square_with_one_edge_against_grey_is_hidden() {
        let truth: [Xy; 4] = [[10.0, 10.0], [30.0, 10.0], [30.0, 30.0], [10.0, 30.0]];
        let mut frame = square(42, 42, truth);
        // Grey (between the dark 40 and the light 200) against the left edge.
        for y in 0..42 {
            for x in 0..10 {
                frame.data[y * 42 + x] = 120;
            }
        }
        let start = truth.map(|[x, y]| [x as f32, y as f32]);
        assert_eq!(refine(&frame, start), Refined::Hidden);
    }
}
