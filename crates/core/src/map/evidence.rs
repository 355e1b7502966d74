//! The sensor layer: log-odds occupancy from lidar beams, camera sight lines and the
//! robot's own footprint (Thrun et al., Probabilistic Robotics, section 9.2), and for
//! every cell the number of occupied cells within the lethal and inflated radii.

/// A cell becomes occupied at this log-odds (about two hits) and stays so down to
/// `RELEASE`: the hysteresis keeps a noisy wall edge from flickering.
const OCCUPY: f32 = 1.2;
const RELEASE: f32 = 0.0;
/// Clamping keeps a cell able to change its mind (as OctoMap does: Hornung et al. 2013).
const MIN_LOG_ODDS: f32 = -2.0;
const MAX_LOG_ODDS: f32 = 3.5;

/// Per-cell evidence on a `width` x `height` grid.
#[derive(Clone, Debug)]
pub struct Evidence {
    width: usize,
    height: usize,
    log_odds: Vec<f32>,
    occupied: Vec<bool>,
    /// Occupied cells within the lethal radius of this cell, and within the inflated one.
    pub near_lethal: Vec<u16>,
    pub near_inflated: Vec<u16>,
    /// Disc offsets (dx, dy, within lethal radius) of the inflated radius, computed once.
    disc: Vec<(i32, i32, bool)>,
}

impl Evidence {
    /// `lethal` and `inflated` are radii in cells.
    pub fn new(width: usize, height: usize, lethal: f64, inflated: f64) -> Self {
        let reach = inflated.max(lethal).ceil() as i32;
        let mut disc = Vec::new();
        for dy in -reach..=reach {
            for dx in -reach..=reach {
                let d = f64::from(dx).hypot(f64::from(dy));
                if d <= inflated.max(lethal) {
                    disc.push((dx, dy, d <= lethal));
                }
            }
        }
        let n = width * height;
        Self {
            width,
            height,
            log_odds: vec![0.0; n],
            occupied: vec![false; n],
            near_lethal: vec![0; n],
            near_inflated: vec![0; n],
            disc,
        }
    }

    /// Whether anything has been observed at cell `i`.
    pub fn known(&self, i: usize) -> bool {
        self.log_odds[i] != 0.0
    }

    /// Every cell's log-odds, row-major: zero where nothing was ever seen.
    pub fn log_odds(&self) -> &[f32] {
        &self.log_odds
    }

    /// Every cell's occupied flag, row-major.
    pub fn occupied(&self) -> &[bool] {
        &self.occupied
    }

    pub fn is_occupied(&self, i: usize) -> bool {
        self.occupied[i]
    }

    /// Adds `delta` log-odds at cell (cx, cy); cells whose counts changed are pushed to
    /// `touched` (the cell itself when only its knowledge changed).
    pub fn add(&mut self, cx: usize, cy: usize, delta: f32, touched: &mut Vec<usize>) {
        let i = cy * self.width + cx;
        let before = self.log_odds[i];
        // Log-odds update, l_t = l_{t-1} + l_obs (Probabilistic Robotics, table 9.1).
        let after = (before + delta).clamp(MIN_LOG_ODDS, MAX_LOG_ODDS);
        if after == before {
            return;
        }
        self.log_odds[i] = after;
        if before == 0.0 {
            touched.push(i);
        }
        let was = self.occupied[i];
        let now = if was {
            after > RELEASE
        } else {
            after >= OCCUPY
        };
        if now != was {
            self.occupied[i] = now;
            self.stamp(cx, cy, now, touched);
        }
    }

    /// Adds (or removes) one occupied cell's contribution to its neighbours' counts.
    fn stamp(&mut self, cx: usize, cy: usize, add: bool, touched: &mut Vec<usize>) {
        for k in 0..self.disc.len() {
            let (dx, dy, lethal) = self.disc[k];
            let (x, y) = (cx as i32 + dx, cy as i32 + dy);
            if x < 0 || y < 0 || x >= self.width as i32 || y >= self.height as i32 {
                continue;
            }
            let j = y as usize * self.width + x as usize;
            let counts = if lethal {
                &mut self.near_lethal
            } else {
                &mut self.near_inflated
            };
            counts[j] = if add {
                counts[j].saturating_add(1)
            } else {
                counts[j].saturating_sub(1)
            };
            touched.push(j);
        }
    }
}

impl Evidence {
    /// Takes a whole grid of certain observations at once (`Some(true)` occupied,
    /// `Some(false)` free, `None` unobserved): each observed cell's log-odds goes to its
    /// bound, as `add` with an infinite delta would put it, and every cell's counts are
    /// then recounted in one pass. Stamping each occupied cell's disc costs occupied cells
    /// times the disc's area (a saved map at 1 cm: seconds); the recount costs cells times
    /// the disc's height, with a running sum along each row.
    pub fn absorb(&mut self, observed: &[Option<bool>]) {
        for (i, o) in observed.iter().enumerate().take(self.log_odds.len()) {
            match o {
                Some(true) => {
                    self.log_odds[i] = MAX_LOG_ODDS;
                    self.occupied[i] = true;
                }
                Some(false) => {
                    self.log_odds[i] = MIN_LOG_ODDS;
                    self.occupied[i] = false;
                }
                None => {}
            }
        }
        self.recount();
    }

    /// Recomputes `near_lethal` and `near_inflated` from `occupied`.
    fn recount(&mut self) {
        let (w, h) = (self.width, self.height);
        // Per row offset dy: the disc's lethal span and its whole span, as dx bounds.
        let mut spans: std::collections::BTreeMap<i32, [(i32, i32); 2]> = Default::default();
        for &(dx, dy, lethal) in &self.disc {
            let e = spans.entry(dy).or_insert([(i32::MAX, i32::MIN); 2]);
            e[1] = (e[1].0.min(dx), e[1].1.max(dx));
            if lethal {
                e[0] = (e[0].0.min(dx), e[0].1.max(dx));
            }
        }
        // prefix[y][x]: occupied cells in row y left of x.
        let mut prefix = vec![0u32; (w + 1) * h];
        for y in 0..h {
            for x in 0..w {
                let o = u32::from(self.occupied[y * w + x]);
                prefix[y * (w + 1) + x + 1] = prefix[y * (w + 1) + x] + o;
            }
        }
        let row_sum = |y: usize, x: i64, lo: i32, hi: i32| -> u32 {
            let a = (x + i64::from(lo)).clamp(0, w as i64) as usize;
            let b = (x + i64::from(hi) + 1).clamp(0, w as i64) as usize;
            if b > a {
                prefix[y * (w + 1) + b] - prefix[y * (w + 1) + a]
            } else {
                0
            }
        };
        // Each row's occupied columns, first and last: a row far from every occupied cell
        // is all zeros, and so is a column far from them.
        let bounds: Vec<Option<(usize, usize)>> = (0..h)
            .map(|y| {
                let row = &self.occupied[y * w..(y + 1) * w];
                let first = row.iter().position(|&o| o)?;
                let last = row.iter().rposition(|&o| o)?;
                Some((first, last))
            })
            .collect();
        let reach = spans
            .keys()
            .map(|dy| dy.unsigned_abs() as usize)
            .max()
            .unwrap_or(0);
        let wide = spans
            .values()
            .map(|s| s[1].0.unsigned_abs().max(s[1].1.unsigned_abs()))
            .max();
        let wide = wide.unwrap_or(0) as usize;
        self.near_lethal.iter_mut().for_each(|c| *c = 0);
        self.near_inflated.iter_mut().for_each(|c| *c = 0);
        for y in 0..h {
            let band = (y.saturating_sub(reach)..=(y + reach).min(h - 1)).filter_map(|r| bounds[r]);
            let Some((lo, hi)) = band.reduce(|a, b| (a.0.min(b.0), a.1.max(b.1))) else {
                continue;
            };
            for x in lo.saturating_sub(wide)..=(hi + wide).min(w - 1) {
                let (mut lethal, mut all) = (0u32, 0u32);
                for (&dy, span) in &spans {
                    let yy = y as i64 + i64::from(dy);
                    if yy < 0 || yy >= h as i64 {
                        continue;
                    }
                    let yy = yy as usize;
                    all += row_sum(yy, x as i64, span[1].0, span[1].1);
                    if span[0].0 <= span[0].1 {
                        lethal += row_sum(yy, x as i64, span[0].0, span[0].1);
                    }
                }
                let i = y * w + x;
                self.near_lethal[i] = lethal.min(u32::from(u16::MAX)) as u16;
                self.near_inflated[i] = (all - lethal).min(u32::from(u16::MAX)) as u16;
            }
        }
    }
}

/// A clipped segment's ends, and whether its far end is the original one.
pub type ClippedSegment = ((f64, f64), (f64, f64), bool);

/// The part of the segment `from`-`to` inside the rectangle `lo`..`hi`, and whether `to`
/// itself is inside: a beam is traced only to the map's edge, however far it claims to
/// reach (Liang and Barsky, "A New Concept and Method for Line Clipping", 1984). A
/// segment wholly inside comes back unchanged; one outside, or not finite, is None.
pub fn clip_segment(
    from: (f64, f64),
    to: (f64, f64),
    lo: (f64, f64),
    hi: (f64, f64),
) -> Option<ClippedSegment> {
    let inside = |p: (f64, f64)| p.0 >= lo.0 && p.0 <= hi.0 && p.1 >= lo.1 && p.1 <= hi.1;
    if inside(from) && inside(to) {
        return Some((from, to, true));
    }
    let (dx, dy) = (to.0 - from.0, to.1 - from.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    // Each edge as p t <= q: left, right, bottom, top.
    for (p, q) in [
        (-dx, from.0 - lo.0),
        (dx, hi.0 - from.0),
        (-dy, from.1 - lo.1),
        (dy, hi.1 - from.1),
    ] {
        if !(p.is_finite() && q.is_finite()) {
            return None;
        }
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else if p < 0.0 {
            t0 = t0.max(q / p);
        } else {
            t1 = t1.min(q / p);
        }
    }
    if t0 > t1 {
        return None;
    }
    let at = |t: f64| (from.0 + t * dx, from.1 + t * dy);
    let start = if t0 > 0.0 { at(t0) } else { from };
    Some(if t1 < 1.0 {
        (start, at(t1), false)
    } else {
        (start, to, true)
    })
}

/// Cells from (x0, y0) to (x1, y1) inclusive, by Bresenham's line algorithm.
pub fn line_cells(x0: i64, y0: i64, x1: i64, y1: i64, mut visit: impl FnMut(i64, i64)) {
    let (dx, dy) = ((x1 - x0).abs(), -(y1 - y0).abs());
    let (sx, sy) = (if x0 < x1 { 1 } else { -1 }, if y0 < y1 { 1 } else { -1 });
    let (mut x, mut y, mut err) = (x0, y0, dx + dy);
    loop {
        visit(x, y);
        if x == x1 && y == y1 {
            return;
        }
        let e2 = 2 * err;
        if e2 >= dy {
            err += dy;
            x += sx;
        }
        if e2 <= dx {
            err += dx;
            y += sy;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_hits_occupy_and_inflate_a_cell_misses_clear_it() {
        let mut e = Evidence::new(50, 50, 3.0, 6.0);
        let mut touched = Vec::new();
        e.add(25, 25, 0.85, &mut touched);
        assert!(!e.is_occupied(25 * 50 + 25));
        e.add(25, 25, 0.85, &mut touched);
        assert!(e.is_occupied(25 * 50 + 25));
        assert_eq!(e.near_lethal[25 * 50 + 28], 1);
        assert_eq!(e.near_lethal[25 * 50 + 29], 0);
        assert_eq!(e.near_inflated[25 * 50 + 30], 1);
        for _ in 0..5 {
            e.add(25, 25, -0.4, &mut touched);
        }
        assert!(!e.is_occupied(25 * 50 + 25));
        assert_eq!(e.near_lethal[25 * 50 + 28], 0);
    }

    #[test]
    fn segments_are_clipped_to_the_rectangle_and_kept_whole_inside_it() {
        let (lo, hi) = ((0.0, 0.0), (10.0, 5.0));
        let inside = clip_segment((1.0, 1.0), (2.0, 3.0), lo, hi);
        assert_eq!(inside, Some(((1.0, 1.0), (2.0, 3.0), true)));
        let (a, b, kept) = clip_segment((1.0, 1.0), (1e308, 1.0), lo, hi).unwrap();
        assert_eq!((a, b, kept), ((1.0, 1.0), (10.0, 1.0), false));
        let (a, b, _) = clip_segment((-5.0, 2.0), (5.0, 2.0), lo, hi).unwrap();
        assert_eq!((a, b), ((0.0, 2.0), (5.0, 2.0)));
        let (_, end, _) = clip_segment((1.0, 1.0), (1.0, -1e308), lo, hi).unwrap();
        assert!(
            (end.0 - 1.0).abs() < 1e-12 && end.1.abs() < 1e-12,
            "{end:?}"
        );
        assert_eq!(clip_segment((-1.0, -1.0), (-2.0, 9.0), lo, hi), None);
        assert_eq!(clip_segment((1.0, 1.0), (f64::INFINITY, 1.0), lo, hi), None);
        assert_eq!(clip_segment((f64::NAN, 1.0), (1.0, 1.0), lo, hi), None);
    }

    #[test]
    fn bresenham_visits_both_ends_contiguously() {
        let mut cells = Vec::new();
        line_cells(0, 0, 5, -3, |x, y| cells.push((x, y)));
        assert_eq!(cells.first(), Some(&(0, 0)));
        assert_eq!(cells.last(), Some(&(5, -3)));
        assert_eq!(cells.len(), 6);
    }

    #[test]
    fn absorbing_a_grid_counts_as_adding_its_cells_one_by_one() {
        // A dense pattern, and a sparse one with empty rows and far columns.
        let dense = |i: usize| match (i * 7919) % 11 {
            0 => Some(true),
            1..=6 => Some(false),
            _ => None,
        };
        let sparse = |i: usize| match i {
            130 | 131 | 1777 => Some(true),
            _ if i.is_multiple_of(3) => Some(false),
            _ => None,
        };
        for (w, h, pattern) in [
            (37, 23, &dense as &dyn Fn(usize) -> Option<bool>),
            (61, 47, &sparse),
        ] {
            let observed: Vec<Option<bool>> = (0..w * h).map(pattern).collect();
            let mut one_by_one = Evidence::new(w, h, 2.5, 4.2);
            let mut touched = Vec::new();
            for (i, o) in observed.iter().enumerate() {
                let delta = match o {
                    Some(true) => f32::INFINITY,
                    Some(false) => f32::NEG_INFINITY,
                    None => continue,
                };
                one_by_one.add(i % w, i / w, delta, &mut touched);
            }
            let mut at_once = Evidence::new(w, h, 2.5, 4.2);
            at_once.absorb(&observed);
            assert_eq!(at_once.occupied, one_by_one.occupied);
            assert_eq!(at_once.log_odds, one_by_one.log_odds);
            assert_eq!(at_once.near_lethal, one_by_one.near_lethal);
            assert_eq!(at_once.near_inflated, one_by_one.near_inflated);
        }
    }
}
