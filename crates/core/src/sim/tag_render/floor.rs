//! The warehouse floor under the tag camera: plain light grey concrete with a fine speckle
//! fixed to the floor, lit a little unevenly (a slow ripple across the floor and the
//! lens's darker corners), and the sensor's noise on every frame. All of it comes from
//! the renderer's seed and the caller's generator.

use crate::sim::noise_bank::NoiseBank;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use std::f64::consts::TAU;

/// Grey level of the bare floor under full light.
pub const FLOOR: f32 = 170.0;
/// Speckle cells on the floor, metres (about three pixels at the default camera), and
/// how far a cell's grey strays from `FLOOR`, levels.
const SPECKLE_CELL: f64 = 0.001;
const SPECKLE: f32 = 6.0;
/// The light's ripple across the floor: ± this fraction, over waves of 2 to 4 m.
const RIPPLE: f64 = 0.12;
/// The lens's corners darker by this fraction than its centre (a mild vignette).
const VIGNETTE: f32 = 0.15;

/// Speckle cells along each side of the speckle's tile, which repeats across the floor.
const TILE: usize = 1024;

/// A whole number of tiles, added before truncating so that truncation floors.
const SHIFT: f64 = (TILE * TILE) as f64;
/// Fractional bits of the fixed-point cell coordinates along a row.
const FRACTION: u32 = 32;
const FIXED_ONE: f64 = (1u64 << FRACTION) as f64;

/// floor(`v`) wrapped into a tile's cells, for |v| under `SHIFT`: the shift makes the
/// value positive, where a cast's truncation is the floor (and, unlike `f64::floor` on
/// x86-64 without SSE4.1, is one instruction).
#[inline(always)]
fn floor_index(v: f64) -> usize {
    (v + SHIFT) as usize
}

/// How the floor and the light on it vary, fixed by the seed.
#[derive(Clone)]
pub struct FloorShade {
    /// Each speckle cell's grey, row by row: a tile of `TILE` x `TILE` cells repeated
    /// (1.024 m across, far wider than the camera's view).
    tile: Vec<u8>,
    /// The ripple's wavenumbers (rad/m) and phases along x and y.
    wave: [f64; 4],
}

impl std::fmt::Debug for FloorShade {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FloorShade")
            .field("wave", &self.wave)
            .finish_non_exhaustive()
    }
}

impl FloorShade {
    pub fn new(rng: &mut ChaCha8Rng) -> Self {
        let wavenumber = |rng: &mut ChaCha8Rng| TAU / rng.random_range(2.0..4.0);
        let spread = 2.0 * SPECKLE;
        let tile = (0..TILE * TILE)
            .map(|_| (FLOOR - SPECKLE + spread * rng.random::<f32>()).round() as u8)
            .collect();
        Self {
            tile,
            wave: [
                wavenumber(rng),
                rng.random_range(0.0..TAU),
                wavenumber(rng),
                rng.random_range(0.0..TAU),
            ],
        }
    }

    /// The floor's grey at world point (`x`, `y`) before the light: `FLOOR` and its
    /// cell's speckle.
    #[inline(always)]
    pub fn grey(&self, [x, y]: [f64; 2]) -> f32 {
        let i = floor_index(x * (1.0 / SPECKLE_CELL)) & (TILE - 1);
        let j = floor_index(y * (1.0 / SPECKLE_CELL)) & (TILE - 1);
        f32::from(self.tile[j * TILE + i])
    }

    /// Paints the floor along a row of pixels `out` (row `v`), the first seeing floor
    /// point `start` and each next one `step` further, lit by `light`. The speckle cells
    /// are walked in fixed point (incremental texture mapping along a scanline, Heckbert
    /// 1989), so no pixel converts a coordinate.
    pub fn paint_row(
        &self,
        start: [f64; 2],
        step: [f64; 2],
        light: &FrameLight,
        v: f32,
        out: &mut [u8],
    ) {
        let fixed = |c: f64| ((c / SPECKLE_CELL + SHIFT) * FIXED_ONE) as i64;
        let (mut gx, mut gy) = (fixed(start[0]), fixed(start[1]));
        let dx = (step[0] / SPECKLE_CELL * FIXED_ONE) as i64;
        let dy = (step[1] / SPECKLE_CELL * FIXED_ONE) as i64;
        let mask = (TILE - 1) as i64;
        for (u, pixel) in out.iter_mut().enumerate() {
            let (i, j) = ((gx >> FRACTION) & mask, (gy >> FRACTION) & mask);
            let grey = f32::from(self.tile[j as usize * TILE + i as usize]);
            // A cast saturates: rounded to the nearest level and held to 0..=255.
            *pixel = (grey * light.at(u as f32, v) + 0.5) as u8;
            gx += dx;
            gy += dy;
        }
    }

    /// The light at world point (`x`, `y`): 1 ± `RIPPLE` (a product of two sines).
    pub fn light(&self, [x, y]: [f64; 2]) -> f64 {
        let [kx, px, ky, py] = self.wave;
        1.0 + RIPPLE * (kx * x + px).sin() * (ky * y + py).sin()
    }
}

/// The light over one frame: the floor's light at the image's corners blended across it
/// (bilinear in the pixel), times the vignette (1 - `VIGNETTE` r², r the distance from
/// the centre over the half diagonal).
#[derive(Clone, Copy, Debug)]
pub struct FrameLight {
    /// Light at the top-left, top-right, bottom-left and bottom-right corners.
    corners: [f32; 4],
    inv_width: f32,
    inv_height: f32,
    centre: [f32; 2],
    inv_radius2: f32,
}

impl FrameLight {
    pub fn new(corners: [f64; 4], width: usize, height: usize) -> Self {
        let (w, h) = (width.max(2) as f32 - 1.0, height.max(2) as f32 - 1.0);
        let centre = [w / 2.0, h / 2.0];
        Self {
            corners: corners.map(|c| c as f32),
            inv_width: 1.0 / w,
            inv_height: 1.0 / h,
            centre,
            inv_radius2: 1.0 / (centre[0] * centre[0] + centre[1] * centre[1]).max(1.0),
        }
    }

    /// The light at pixel (`u`, `v`).
    #[inline]
    pub fn at(&self, u: f32, v: f32) -> f32 {
        let (a, b) = (u * self.inv_width, v * self.inv_height);
        let [tl, tr, bl, br] = self.corners;
        let top = tl + (tr - tl) * a;
        let bottom = bl + (br - bl) * a;
        let (du, dv) = (u - self.centre[0], v - self.centre[1]);
        (top + (bottom - top) * b) * (1.0 - VIGNETTE * (du * du + dv * dv) * self.inv_radius2)
    }
}

/// The tag camera's bank: `len` grey-level offsets of `sd` levels of standard deviation,
/// each the centred sum of two random bytes (triangular, variance 2 (256² - 1) / 12 for
/// independent discrete uniforms), scaled to `sd`.
pub fn noise_bank(sd: f64, len: usize, rng: &mut ChaCha8Rng) -> NoiseBank {
    let scale = sd / (2.0 * (256.0f64 * 256.0 - 1.0) / 12.0).sqrt();
    let mut bytes = vec![0u8; 2 * len.max(1)];
    rng.fill(&mut bytes[..]);
    NoiseBank::of(
        (bytes.chunks_exact(2))
            .map(|b| ((f64::from(b[0]) + f64::from(b[1]) - 255.0) * scale).round() as i8)
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn the_floor_is_light_grey_within_its_speckle_and_the_same_each_time() {
        let shade = FloorShade::new(&mut ChaCha8Rng::seed_from_u64(3));
        let greys: Vec<f32> = (0..1000)
            .map(|i| shade.grey([f64::from(i) * 0.0013, -0.5]))
            .collect();
        assert!(greys.iter().all(|g| (g - FLOOR).abs() <= SPECKLE));
        let mean = greys.iter().sum::<f32>() / 1000.0;
        assert!((mean - FLOOR).abs() < 0.5, "{mean}");
        // Either side of zero the cells run on evenly.
        assert_eq!(floor_index(-0.5) & (TILE - 1), TILE - 1);
        assert_eq!(floor_index(0.5) & (TILE - 1), 0);
        // A row painted in fixed point reads the cells a pixel at a time would (no
        // pixel of this row falls within a thousandth of a cell of an edge).
        let light = FrameLight::new([1.0; 4], 101, 3);
        let mut row = [0u8; 101];
        let (start, step) = ([-0.01231, 0.45677], [0.000311, -0.000173]);
        shade.paint_row(start, step, &light, 1.0, &mut row);
        for (u, &grey) in row.iter().enumerate() {
            let t = u as f64;
            let p = [start[0] + t * step[0], start[1] + t * step[1]];
            let want = (shade.grey(p) * light.at(u as f32, 1.0) + 0.5) as u8;
            assert_eq!(grey, want, "pixel {u}");
        }
        // The speckle repeats 1.024 m on.
        assert_eq!(shade.grey([0.2505, 0.7005]), shade.grey([1.2745, -0.3235]));
        assert_eq!(shade.grey([0.3, 0.2]), shade.grey([0.3, 0.2]));
        let light = shade.light([1.0, 2.0]);
        assert!((1.0 - RIPPLE..=1.0 + RIPPLE).contains(&light), "{light}");
    }

    #[test]
    fn the_frames_light_blends_its_corners_and_darkens_them() {
        let l = FrameLight::new([1.0, 1.0, 0.9, 0.9], 101, 51);
        // The centre: halfway between the rows' light, no vignette.
        assert!((l.at(50.0, 25.0) - 0.95).abs() < 1e-6);
        // A corner: its own light less the full vignette.
        assert!((l.at(0.0, 0.0) - (1.0 - VIGNETTE)).abs() < 1e-6);
    }

    #[test]
    fn the_noise_has_about_the_standard_deviation_asked() {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let bank = noise_bank(2.0, 1 << 16, &mut rng);
        let mut pixels = vec![100u8; 1 << 16];
        bank.add(&mut pixels, &mut rng);
        let (mean, sd) = crate::sim::noise_bank::spread(&pixels);
        assert!((mean - 100.0).abs() < 0.05, "{mean}");
        assert!((sd - 2.0).abs() < 0.1, "{sd}");
    }
}
