//! What makes the beam model affordable: the ranges traced from each cell a particle has
//! stood in, remembered per half degree of bearing (traced from the cell's centre, as
//! AMCL traces from the particle's cell), and ln p(z | z*) tabulated over measured and
//! expected range. A particle in a cell visited before costs a table look-up per beam
//! instead of a ray cast, an exponential and a logarithm.

use super::config::MeasurementModel;
use super::known_map::KnownMap;
use super::sensor::beam_probability;
use std::collections::HashMap;

/// Bearings remembered per cell: every half degree.
const BEARINGS: usize = 720;
/// Range steps of the table: the sensor's range in this many.
const STEPS: usize = 512;
/// Cells remembered before the memo starts afresh (about 30 MB).
const MOST_CELLS: usize = 20_000;
/// A bearing not traced yet.
const UNTRACED: u16 = u16::MAX;

/// ln p(z | z*) over measured and expected range, each in `STEPS` steps of the range.
#[derive(Clone, Debug)]
pub struct BeamTable {
    step: f64,
    log_p: Vec<f32>,
}

impl BeamTable {
    pub fn new(config: &MeasurementModel, max_range: f64) -> Self {
        let step = max_range / STEPS as f64;
        let n = STEPS + 1;
        let mut log_p = Vec::with_capacity(n * n);
        for zi in 0..n {
            for ei in 0..n {
                let (z, e) = (zi as f64 * step, ei as f64 * step);
                log_p.push(beam_probability(z, e, max_range, config).ln() as f32);
            }
        }
        Self { step, log_p }
    }

    /// The step index of a range.
    #[inline]
    pub fn index(&self, range: f64) -> usize {
        ((range / self.step).round().max(0.0) as usize).min(STEPS)
    }

    #[inline]
    pub fn log_p(&self, z: usize, expected: usize) -> f32 {
        self.log_p[z * (STEPS + 1) + expected]
    }
}

/// Traced ranges (as table step indices) per cell and bearing.
#[derive(Clone, Debug, Default)]
pub struct RangeMemo {
    rows: HashMap<u32, Box<[u16]>>,
}

impl RangeMemo {
    /// The expected range's index from `cell` along world bearing `angle`.
    pub fn expected(
        &mut self,
        map: &KnownMap,
        table: &BeamTable,
        cell: usize,
        angle: f64,
        max_range: f64,
    ) -> usize {
        if self.rows.len() >= MOST_CELLS && !self.rows.contains_key(&(cell as u32)) {
            self.rows.clear();
        }
        let row = self
            .rows
            .entry(cell as u32)
            .or_insert_with(|| vec![UNTRACED; BEARINGS].into_boxed_slice());
        let turn = std::f64::consts::TAU;
        let bin = ((angle.rem_euclid(turn) / turn * BEARINGS as f64).round() as usize) % BEARINGS;
        if row[bin] == UNTRACED {
            let a = bin as f64 * turn / BEARINGS as f64;
            let from = map.center(cell);
            let r = map.ray_cast(from.x, from.y, a.cos(), a.sin(), max_range);
            row[bin] = table.index(r) as u16;
        }
        usize::from(row[bin])
    }

    /// Forgets every traced range.
    pub fn clear(&mut self) {
        self.rows.clear();
    }

    pub fn cells(&self) -> usize {
        self.rows.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Point2;
    use crate::map::grid::OccupancyGrid;

    #[test]
    fn the_table_agrees_with_the_model_at_its_steps() {
        let c = MeasurementModel::default();
        let t = BeamTable::new(&c, 3.5);
        let (zi, ei) = (t.index(2.0), t.index(1.0));
        let (z, e) = (zi as f64 * t.step, ei as f64 * t.step);
        let exact = beam_probability(z, e, 3.5, &c).ln();
        assert!((f64::from(t.log_p(zi, ei)) - exact).abs() < 1e-5);
        // A maximum-range reading has its own entry: only z_max.
        let top = t.index(3.5);
        assert!((f64::from(t.log_p(top, ei)) - 0.05f64.ln()).abs() < 1e-6);
    }

    #[test]
    fn a_remembered_range_is_the_one_traced_from_the_cell() {
        // A wall at x = 2 m; from the cell at (1.025, 1.025) facing +x it is 0.95 m away.
        let mut g = OccupancyGrid::new(80, 40, 0.05, Point2::new(0.0, 0.0), 0);
        for y in 0..40 {
            g.set(40, y, 100);
        }
        let map = KnownMap::new(&g).unwrap();
        let table = BeamTable::new(&MeasurementModel::default(), 3.5);
        let mut memo = RangeMemo::default();
        let cell = map.index_of(1.03, 1.03).unwrap();
        let first = memo.expected(&map, &table, cell, 0.001, 3.5);
        let again = memo.expected(&map, &table, cell, 0.0, 3.5);
        assert_eq!(first, again);
        assert_eq!(first, table.index(0.975));
        assert_eq!(memo.cells(), 1);
    }
}
