//! The grid scans are matched against: each cell holds how likely a beam ending there is,
//! given the hits of the keyframes it was built from, a Gaussian of the distance to the
//! nearest hit (Olson, "Real-Time Correlative Scan Matching", 2009, section III; the
//! likelihood field of Probabilistic Robotics 6.4).

use crate::geometry::Point2;

/// A likelihood grid and a coarser copy holding each block's best value, for the
/// coarse-to-fine search (Olson 2009, section IV: the low-resolution table's cell is the
/// maximum of the cells it covers, so a coarse score never undercuts a fine one).
#[derive(Clone, Debug)]
pub struct Field {
    pub origin: Point2,
    pub resolution: f64,
    pub width: usize,
    pub height: usize,
    pub values: Vec<f32>,
}

/// Cells beyond the hits' box kept round it: a beam may end a little past the mapped
/// walls, and the search moves the scan.
const PAD_CELLS: usize = 4;
/// Largest grid side, cells: 60 m at 5 cm, beyond any room a 3.5 m lidar maps at once.
const MAX_SIDE_CELLS: usize = 1200;

impl Field {
    /// The field of `hits` (world points) at `resolution` with Gaussian spread `smear`,
    /// padded by `pad` metres; `None` without hits or when the hits span more than the
    /// largest grid.
    pub fn from_hits(hits: &[Point2], resolution: f64, smear: f64, pad: f64) -> Option<Field> {
        let first = hits.first()?;
        let (mut lo, mut hi) = (*first, *first);
        for p in hits {
            lo = Point2::new(lo.x.min(p.x), lo.y.min(p.y));
            hi = Point2::new(hi.x.max(p.x), hi.y.max(p.y));
        }
        let margin = pad + PAD_CELLS as f64 * resolution;
        let origin = Point2::new(lo.x - margin, lo.y - margin);
        let width = ((hi.x - lo.x + 2.0 * margin) / resolution).ceil() as usize + 1;
        let height = ((hi.y - lo.y + 2.0 * margin) / resolution).ceil() as usize + 1;
        if width > MAX_SIDE_CELLS || height > MAX_SIDE_CELLS {
            return None;
        }
        let mut values = vec![0.0f32; width * height];
        // Each hit raises the cells within three deviations to exp(-d² / 2σ²), d the exact
        // distance from the hit to the cell's centre (Olson 2009 eq. 5's Gaussian blur of a
        // hit; Karto's smear kernel), so that interpolating between cells finds the hit
        // to a fraction of a cell.
        let reach = (3.0 * smear / resolution).ceil() as i64;
        let k = 1.0 / (2.0 * smear * smear);
        let side = 2 * reach as usize + 1;
        let (mut along_x, mut along_y) = (vec![0.0f32; side], vec![0.0f32; side]);
        for p in hits {
            let (fx, fy) = ((p.x - origin.x) / resolution, (p.y - origin.y) / resolution);
            let (cx, cy) = (fx as i64, fy as i64);
            // The Gaussian is separable: exp(-(dx² + dy²) k) = exp(-dx² k) exp(-dy² k).
            for (j, d) in (-reach..=reach).enumerate() {
                let dx = ((cx + d) as f64 + 0.5 - fx) * resolution;
                let dy = ((cy + d) as f64 + 0.5 - fy) * resolution;
                along_x[j] = (-(dx * dx) * k).exp() as f32;
                along_y[j] = (-(dy * dy) * k).exp() as f32;
            }
            for (j, y) in (cy - reach..=cy + reach).enumerate() {
                if y < 0 || y >= height as i64 {
                    continue;
                }
                let row = &mut values[y as usize * width..(y as usize + 1) * width];
                for (i, x) in (cx - reach..=cx + reach).enumerate() {
                    if x < 0 || x >= width as i64 {
                        continue;
                    }
                    let cell = &mut row[x as usize];
                    *cell = cell.max(along_x[i] * along_y[j]);
                }
            }
        }
        Some(Field {
            origin,
            resolution,
            width,
            height,
            values,
        })
    }

    /// The field at half the resolution, each cell the best of the four it covers.
    pub fn coarser(&self) -> Field {
        let (w, h) = (self.width.div_ceil(2), self.height.div_ceil(2));
        let mut values = vec![0.0f32; w * h];
        for y in 0..self.height {
            for x in 0..self.width {
                let v = self.values[y * self.width + x];
                let c = &mut values[(y / 2) * w + x / 2];
                *c = c.max(v);
            }
        }
        Field {
            origin: self.origin,
            resolution: 2.0 * self.resolution,
            width: w,
            height: h,
            values,
        }
    }

    /// The value of the cell holding `(x, y)` (world), 0 off the grid.
    #[cfg(test)]
    pub fn at(&self, x: f64, y: f64) -> f32 {
        let fx = (x - self.origin.x) / self.resolution;
        let fy = (y - self.origin.y) / self.resolution;
        if fx < 0.0 || fy < 0.0 {
            return 0.0;
        }
        let (cx, cy) = (fx as usize, fy as usize);
        if cx >= self.width || cy >= self.height {
            return 0.0;
        }
        self.values[cy * self.width + cx]
    }

    /// The value at `(x, y)` interpolated between the four nearest cell centres.
    pub fn bilinear(&self, x: f64, y: f64) -> f64 {
        let fx = (x - self.origin.x) / self.resolution - 0.5;
        let fy = (y - self.origin.y) / self.resolution - 0.5;
        if fx < 0.0 || fy < 0.0 {
            return 0.0;
        }
        let (cx, cy) = (fx as usize, fy as usize);
        if cx + 1 >= self.width || cy + 1 >= self.height {
            return 0.0;
        }
        let (tx, ty) = (fx - cx as f64, fy - cy as f64);
        let v = |x: usize, y: usize| f64::from(self.values[y * self.width + x]);
        let bottom = v(cx, cy) * (1.0 - tx) + v(cx + 1, cy) * tx;
        let top = v(cx, cy + 1) * (1.0 - tx) + v(cx + 1, cy + 1) * tx;
        bottom * (1.0 - ty) + top * ty
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_hit_is_near_one_and_falls_off_as_a_gaussian() {
        let f = Field::from_hits(&[Point2::new(1.0, 1.0)], 0.05, 0.05, 0.5).unwrap();
        // Within half a cell's diagonal of the centre: exp(-(0.0354²) / 0.005) = 0.779.
        assert!(f.at(1.0, 1.0) > 0.77, "{}", f.at(1.0, 1.0));
        assert!(f.bilinear(1.0, 1.0) > 0.77, "{}", f.bilinear(1.0, 1.0));
        // 0.1 m away: exp(-0.01 / 0.005) = exp(-2), to within the cells' interpolation.
        let two = f.bilinear(1.1, 1.0);
        assert!((two - (-2.0f64).exp()).abs() < 0.05, "{two}");
        assert!(f.bilinear(1.2, 1.0) < two);
        assert_eq!(f.at(-50.0, 0.0), 0.0);
        let coarse = f.coarser();
        assert!(coarse.at(1.0, 1.0) >= f.at(1.0, 1.0));
    }

    #[test]
    fn no_hits_or_too_wide_is_no_field() {
        assert!(Field::from_hits(&[], 0.05, 0.05, 0.5).is_none());
        let wide = [Point2::new(0.0, 0.0), Point2::new(500.0, 0.0)];
        assert!(Field::from_hits(&wide, 0.05, 0.05, 0.5).is_none());
    }
}
