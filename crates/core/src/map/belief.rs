//! The robot's planning map: the landmark layer and the sensor layer combined into one
//! costmap, updated cell by cell as landmarks move and scans arrive — never rebuilt.

use super::config::MapConfig;
use super::contact::HeldZone;
use super::costmap::{Costmap, INFLATED, LETHAL, NO_INFORMATION};
use super::evidence::{Evidence, clip_segment, line_cells};
use super::grid::{OCCUPIED, OccupancyGrid};
use super::landmark_layer::LandmarkLayer;
use crate::data::LaserScan;
use crate::geometry::{Point2, Pose2};

/// A landmark is restamped once its estimate moved this far, metres: the filter nudges
/// every correlated landmark a little with each correction, and two centimetres are well
/// inside the lethal radius's margin for landmark uncertainty.
const LANDMARK_MOVE: f64 = 0.02;

mod keepout;

/// What the robot believes about the space around it, as a costmap for the planner.
#[derive(Clone, Debug)]
pub struct BeliefMap {
    config: MapConfig,
    costmap: Costmap,
    landmark_cost: Vec<u8>,
    landmarks: LandmarkLayer,
    evidence: Evidence,
    revision: u64,
    recomputed: u64,
    touched: Vec<usize>,
    /// The keepout zones' layer (`zones::raster::keepout_costs`) and which zones it shows.
    keepout_cost: Vec<u8>,
    keepout_tag: u64,
}

impl BeliefMap {
    /// An empty map of `extent` metres centred on the origin (seed 001: 4 m x 4 m).
    pub fn new(config: &MapConfig, extent: (f64, f64)) -> Self {
        let origin = Point2::new(-extent.0 / 2.0, -extent.1 / 2.0);
        Self::covering(config, origin, extent)
    }

    /// An empty map of `extent` metres whose lower-left corner is `origin`.
    pub fn covering(config: &MapConfig, origin: Point2, extent: (f64, f64)) -> Self {
        let res = config.resolution;
        let (w, h) = (
            (extent.0 / res).round() as usize,
            (extent.1 / res).round() as usize,
        );
        Self {
            costmap: Costmap::new(w, h, res, origin, NO_INFORMATION),
            landmark_cost: vec![0; w * h],
            landmarks: LandmarkLayer::default(),
            evidence: Evidence::new(
                w,
                h,
                config.lethal_radius / res,
                config.obstacle_inflation / res,
            ),
            revision: 0,
            recomputed: 0,
            touched: Vec::new(),
            keepout_cost: vec![0; w * h],
            keepout_tag: 0,
            config: config.clone(),
        }
    }

    pub fn costmap(&self) -> &Costmap {
        &self.costmap
    }

    /// The cells the sensors found occupied (not the landmark layer), row-major over the
    /// costmap.
    pub fn sensed_occupied(&self) -> &[bool] {
        self.evidence.occupied()
    }

    /// Grows whenever any cell's cost changed.
    pub fn revision(&self) -> u64 {
        self.revision
    }

    /// Takes over from `previous`, a map this one redraws: its revision follows the old
    /// one's, so that whoever drew or planned on the old map sees a change.
    pub fn succeed(&mut self, previous: &BeliefMap) {
        self.revision = previous.revision + 1;
    }

    /// Cells recomputed so far: the work the incremental updates did.
    pub fn recomputed_cells(&self) -> u64 {
        self.recomputed
    }

    /// Takes the filter's landmark means and recomputes the cells around those that moved.
    pub fn update_landmarks(&mut self, estimates: impl IntoIterator<Item = (u32, Point2)>) {
        let dirty = self.landmarks.update(
            estimates,
            &self.config,
            LANDMARK_MOVE.max(self.config.resolution),
        );
        for rect in merged(dirty.iter().map(|s| self.cell_rect(s.bounds()))) {
            self.restamp_area(rect);
        }
    }

    /// Drops the landmarks `ids` (the filter forgot them) and recomputes their cells.
    pub fn drop_landmarks(&mut self, ids: &[u32]) {
        let dirty = self.landmarks.remove(ids, &self.config);
        for rect in merged(dirty.iter().map(|s| self.cell_rect(s.bounds()))) {
            self.restamp_area(rect);
        }
    }

    /// The cells overlapping a world rectangle (x0, y0, x1, y1), clamped to the map.
    fn cell_rect(&self, (x0, y0, x1, y1): (f64, f64, f64, f64)) -> CellRect {
        let map = &self.costmap;
        let clamp = |v: f64, n: usize| (v.floor().max(0.0) as usize).min(n.saturating_sub(1));
        (
            clamp((x0 - map.origin.x) / map.resolution, map.width),
            clamp((y0 - map.origin.y) / map.resolution, map.height),
            clamp((x1 - map.origin.x) / map.resolution, map.width),
            clamp((y1 - map.origin.y) / map.resolution, map.height),
        )
    }

    /// Recomputes the landmark layer over `rect`: cleared, then every stamp reaching into it
    /// drawn over its own part, keeping the highest cost.
    fn restamp_area(&mut self, rect: CellRect) {
        let (c0, r0, c1, r1) = rect;
        for cy in r0..=r1 {
            let row = cy * self.costmap.width;
            self.landmark_cost[row + c0..=row + c1].fill(0);
        }
        for stamp in self.landmarks.stamps() {
            let (sc0, sr0, sc1, sr1) = self.cell_rect(stamp.bounds());
            let (c0, r0, c1, r1) = (c0.max(sc0), r0.max(sr0), c1.min(sc1), r1.min(sr1));
            if c0 > c1 || r0 > r1 {
                continue;
            }
            for cy in r0..=r1 {
                for cx in c0..=c1 {
                    let cost = stamp.cost_at(self.costmap.center_of(cx, cy));
                    let i = self.costmap.index(cx, cy);
                    self.landmark_cost[i] = self.landmark_cost[i].max(cost);
                }
            }
        }
        for cy in r0..=r1 {
            for cx in c0..=c1 {
                self.refresh(self.costmap.index(cx, cy));
            }
        }
    }

    /// Folds a lidar scan taken at `pose` into the sensor layer: the cells a beam crossed
    /// are more likely free, the cell it ended in more likely occupied.
    pub fn observe_scan(&mut self, pose: Pose2, scan: &LaserScan) {
        self.observe_scan_holding(pose, scan, None);
    }

    /// `observe_scan`, leaving out the beams that end in `held`: what the gripper holds
    /// moves with the robot and is not part of the world.
    pub fn observe_scan_holding(&mut self, pose: Pose2, scan: &LaserScan, held: Option<HeldZone>) {
        self.observe_scan_within(pose, scan, held, (|_| true, f64::INFINITY));
    }

    /// `observe_scan_holding`, each beam cut where it first reaches a point `mappable`
    /// refuses, checked every `step` metres along it (beyond a known map's walls): from
    /// there on it adds nothing, not even its hit.
    pub fn observe_scan_within(
        &mut self,
        pose: Pose2,
        scan: &LaserScan,
        held: Option<HeldZone>,
        (mappable, step): (impl Fn(Point2) -> bool, f64),
    ) {
        for (k, &range) in scan.ranges.iter().enumerate() {
            let range = f64::from(range);
            if range.is_nan() || range < scan.range_min {
                continue;
            }
            let hit = range <= scan.range_max;
            let length = range.min(scan.range_max);
            let angle = pose.theta + scan.angle_min + k as f64 * scan.angle_increment;
            let end = Point2::new(pose.x + length * angle.cos(), pose.y + length * angle.sin());
            if hit && held.is_some_and(|z| z.contains(pose, end)) {
                continue;
            }
            // Traced only to near the map's edge: a beam ending beyond adds no hit.
            let Some((_, end, end_inside)) = self.clip_to_map(pose.position(), end) else {
                continue;
            };
            let hit = hit && end_inside;
            let (end, hit) = match cut_at(pose.position(), end, step, &mappable) {
                Some(stop) => (stop, false),
                None => (end, hit),
            };
            self.observe_ray_within(pose.position(), end, hit, &mappable);
        }
    }

    /// A camera saw a marker at `to`: the space up to `stop_short` before it is free.
    pub fn observe_sight_line(&mut self, from: Point2, to: Point2, stop_short: f64) {
        let d = from.distance(to);
        if d <= stop_short {
            return;
        }
        let k = (d - stop_short) / d;
        let end = Point2::new(from.x + k * (to.x - from.x), from.y + k * (to.y - from.y));
        self.observe_ray(from, end, false);
    }

    /// The robot stands here, so its footprint is free.
    pub fn observe_footprint(&mut self, center: Point2, radius: f64) {
        let Some((cx, cy)) = self.costmap.cell_of(center) else {
            return;
        };
        let r = (radius / self.config.resolution).floor() as i64;
        for dy in -r..=r {
            for dx in -r..=r {
                if dx * dx + dy * dy <= r * r {
                    self.add_evidence(cx as i64 + dx, cy as i64 + dy, self.config.miss_log_odds);
                }
            }
        }
        self.flush();
    }

    /// The gripper took hold of what lay in `held` of a robot at `pose`: the cells the
    /// sensors found occupied there are free now (the block left with the robot).
    pub fn clear_held(&mut self, pose: Pose2, held: HeldZone) {
        let map = &self.costmap;
        let reach = held.ahead.hypot(held.half_width);
        let (c0, r0, c1, r1) = self.cell_rect((
            pose.x - reach,
            pose.y - reach,
            pose.x + reach,
            pose.y + reach,
        ));
        let mut cells = Vec::new();
        for cy in r0..=r1 {
            for cx in c0..=c1 {
                let i = map.index(cx, cy);
                if self.evidence.is_occupied(i) && held.contains(pose, map.center_of(cx, cy)) {
                    cells.push((cx as i64, cy as i64));
                }
            }
        }
        for (cx, cy) in cells {
            self.add_evidence(cx, cy, f32::NEG_INFINITY);
        }
        self.flush();
    }

    /// What the sensors found, as an occupancy grid for a map file: occupied, known free,
    /// or unknown (the cost rings are not saved; they are worked out again on load).
    pub fn occupancy_grid(&self) -> OccupancyGrid {
        let c = &self.costmap;
        let grid = OccupancyGrid::new(c.width, c.height, c.resolution, c.origin, -1);
        fill_grid(grid, self.evidence.occupied(), self.evidence.log_odds())
    }

    /// As `occupancy_grid`, but a cell is free only where the evidence says free (more
    /// rays passed through it than ended in it): what a map to be loaded is held against.
    pub fn sensed_grid(&self) -> OccupancyGrid {
        let mut grid = self.occupancy_grid();
        for (cell, &log_odds) in grid.cells.iter_mut().zip(self.evidence.log_odds()) {
            if *cell == 0 && log_odds > 0.0 {
                *cell = -1;
            }
        }
        grid
    }

    /// A copy of the evidence the occupancy grid is made from (a plain copy of two
    /// arrays): a recording makes the grid from it on its writer's thread, off the
    /// control loop.
    pub fn evidence_snapshot(&self) -> EvidenceSnapshot {
        let c = &self.costmap;
        EvidenceSnapshot {
            width: c.width,
            height: c.height,
            resolution: c.resolution,
            origin: c.origin,
            occupied: self.evidence.occupied().to_vec(),
            log_odds: self.evidence.log_odds().to_vec(),
        }
    }

    /// Takes a whole occupancy grid as certain evidence: its occupied cells become
    /// obstacles (inflated as lidar hits are), its free cells free, its unknown stays unknown.
    pub fn absorb_grid(&mut self, grid: &OccupancyGrid) {
        let map = &self.costmap;
        let observed: Vec<Option<bool>> = (0..map.width * map.height)
            .map(|i| {
                let value = grid.at(map.center_of(i % map.width, i / map.width));
                (value >= 0).then_some(value >= OCCUPIED / 2)
            })
            .collect();
        self.evidence.absorb(&observed);
        for i in 0..observed.len() {
            self.refresh(i);
        }
    }

    fn observe_ray(&mut self, from: Point2, to: Point2, hit: bool) {
        self.observe_ray_within(from, to, hit, |_| true);
    }

    /// `observe_ray`, adding nothing to a cell whose centre `mappable` refuses.
    fn observe_ray_within(
        &mut self,
        from: Point2,
        to: Point2,
        hit: bool,
        mappable: impl Fn(Point2) -> bool,
    ) {
        let Some((from, to, to_inside)) = self.clip_to_map(from, to) else {
            return;
        };
        let hit = hit && to_inside;
        let map = &self.costmap;
        let (origin, res) = (map.origin, map.resolution);
        let cell = |p: Point2| {
            (
                ((p.x - map.origin.x) / map.resolution).floor() as i64,
                ((p.y - map.origin.y) / map.resolution).floor() as i64,
            )
        };
        let ((x0, y0), (x1, y1)) = (cell(from), cell(to));
        let (w, h) = (map.width as i64, map.height as i64);
        let (miss, hit_odds) = (self.config.miss_log_odds, self.config.hit_log_odds);
        let (evidence, touched) = (&mut self.evidence, &mut self.touched);
        line_cells(x0, y0, x1, y1, |x, y| {
            if x < 0 || y < 0 || x >= w || y >= h {
                return;
            }
            let centre = Point2::new(
                origin.x + (x as f64 + 0.5) * res,
                origin.y + (y as f64 + 0.5) * res,
            );
            if !mappable(centre) {
                return;
            }
            let delta = if hit && (x, y) == (x1, y1) {
                hit_odds
            } else {
                miss
            };
            evidence.add(x as usize, y as usize, delta, touched);
        });
        self.flush();
    }

    /// The part of `from`-`to` within one map's size of the map (cells out there are
    /// not on it, so a beam is traced as before up to there and no farther, however far
    /// it claims to reach), and whether `to` is within it.
    fn clip_to_map(&self, from: Point2, to: Point2) -> Option<(Point2, Point2, bool)> {
        let map = &self.costmap;
        let size = (
            map.width as f64 * map.resolution,
            map.height as f64 * map.resolution,
        );
        let lo = (map.origin.x - size.0, map.origin.y - size.1);
        let hi = (map.origin.x + 2.0 * size.0, map.origin.y + 2.0 * size.1);
        let (a, b, inside) = clip_segment((from.x, from.y), (to.x, to.y), lo, hi)?;
        Some((Point2::new(a.0, a.1), Point2::new(b.0, b.1), inside))
    }

    fn add_evidence(&mut self, x: i64, y: i64, delta: f32) {
        let (w, h) = (self.costmap.width as i64, self.costmap.height as i64);
        if x < 0 || y < 0 || x >= w || y >= h {
            return;
        }
        self.evidence
            .add(x as usize, y as usize, delta, &mut self.touched);
    }

    /// Recomputes the cells whose evidence changed.
    fn flush(&mut self) {
        let touched = std::mem::take(&mut self.touched);
        for &i in &touched {
            self.refresh(i);
        }
        self.touched = touched;
        self.touched.clear();
    }

    /// The cell's cost: the worst of both layers; no information if neither knows it.
    fn refresh(&mut self, i: usize) {
        self.recomputed += 1;
        let e = &self.evidence;
        let sensed = if e.near_lethal[i] > 0 {
            LETHAL
        } else if e.near_inflated[i] > 0 {
            INFLATED
        } else {
            0
        };
        let mut cost = self.landmark_cost[i].max(sensed).max(self.keepout_cost[i]);
        if cost == 0 && !e.known(i) {
            cost = NO_INFORMATION;
        }
        if self.costmap.cost[i] != cost {
            self.costmap.cost[i] = cost;
            self.revision += 1;
        }
    }
}

/// Inclusive cell rectangle (c0, r0, c1, r1).
type CellRect = (usize, usize, usize, usize);

/// Rectangles with overlapping ones joined into their bounding box, so no cell is
/// recomputed twice for the old and new place of one landmark.
fn merged(rects: impl Iterator<Item = CellRect>) -> Vec<CellRect> {
    let mut out: Vec<CellRect> = Vec::new();
    for mut r in rects {
        while let Some(k) = out
            .iter()
            .position(|o| o.0 <= r.2 && r.0 <= o.2 && o.1 <= r.3 && r.1 <= o.3)
        {
            let o = out.swap_remove(k);
            r = (o.0.min(r.0), o.1.min(r.1), o.2.max(r.2), o.3.max(r.3));
        }
        out.push(r);
    }
    out
}
/// The evidence behind an occupancy grid, copied out of a belief map.
#[derive(Clone, Debug)]
pub struct EvidenceSnapshot {
    width: usize,
    height: usize,
    resolution: f64,
    origin: Point2,
    occupied: Vec<bool>,
    log_odds: Vec<f32>,
}

impl EvidenceSnapshot {
    /// Occupied, known free (evidence either way) or unknown, cell by cell.
    pub fn into_grid(self) -> OccupancyGrid {
        let grid = OccupancyGrid::new(self.width, self.height, self.resolution, self.origin, -1);
        fill_grid(grid, &self.occupied, &self.log_odds)
    }
}

/// The last point `step` apart along `from`-`to` before the first one `mappable` refuses,
/// if any is refused (`from` itself refused: `from`).
fn cut_at(
    from: Point2,
    to: Point2,
    step: f64,
    mappable: impl Fn(Point2) -> bool,
) -> Option<Point2> {
    let length = from.distance(to);
    let n = (length / step).ceil().max(1.0) as usize;
    let mut last = from;
    for k in 0..=n {
        let f = k as f64 / n as f64;
        let p = Point2::new(from.x + f * (to.x - from.x), from.y + f * (to.y - from.y));
        if !mappable(p) {
            return Some(last);
        }
        last = p;
    }
    None
}

/// `grid`'s cells from the evidence: occupied, known free (evidence either way) or unknown.
fn fill_grid(mut grid: OccupancyGrid, occupied: &[bool], log_odds: &[f32]) -> OccupancyGrid {
    // Zipped slices, no indexing: the loop vectorises.
    let cells = occupied.iter().zip(log_odds);
    for (cell, (&occupied, &log_odds)) in grid.cells.iter_mut().zip(cells) {
        *cell = if occupied {
            OCCUPIED
        } else if log_odds != 0.0 {
            0
        } else {
            -1
        };
    }
    grid
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_beam_is_cut_before_the_first_point_outside() {
        let inside = |p: Point2| p.x <= 1.0;
        let from = Point2::new(0.0, 0.0);
        assert_eq!(cut_at(from, Point2::new(0.8, 0.0), 0.1, inside), None);
        let stop = cut_at(from, Point2::new(3.0, 0.0), 0.1, inside).unwrap();
        assert!((stop.x - 1.0).abs() < 0.11 && stop.x <= 1.0, "{stop:?}");
    }
}
