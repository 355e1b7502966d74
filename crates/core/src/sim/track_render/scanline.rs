//! The floor texture read along image rows. On a camera without roll the rays of one
//! row all fall at the same slope, so they meet the floor along a straight line at even
//! steps; a stretch of a row is then walked in fixed point from its first texel
//! (incremental texture mapping along a scanline, Heckbert 1989, "Fundamentals of
//! Texture Mapping and Image Warping") rather than each pixel moved and sampled on its
//! own. `FloorRays` cuts a row wherever the steps are not even.

use super::texture::{FloorTexture, Level};
use crate::geometry::Pose2;

/// Fractional bits of the fixed-point texel coordinates.
const FRACTION: u32 = 16;
const ONE: f64 = (1u64 << FRACTION) as f64;

/// A robot pose as a rigid move of robot-frame floor points into the world.
#[derive(Clone, Copy, Debug)]
pub struct RigidMove {
    sin: f64,
    cos: f64,
    x: f64,
    y: f64,
}

impl RigidMove {
    pub fn of(pose: Pose2) -> Self {
        let (sin, cos) = pose.theta.sin_cos();
        Self {
            sin,
            cos,
            x: pose.x,
            y: pose.y,
        }
    }

    /// The robot-frame point `p` in the world.
    pub fn apply(&self, [x, y]: [f64; 2]) -> [f64; 2] {
        let [rx, ry] = self.rotate([x, y]);
        [self.x + rx, self.y + ry]
    }

    /// The robot-frame vector `v` turned into the world.
    pub fn rotate(&self, [x, y]: [f64; 2]) -> [f64; 2] {
        [self.cos * x - self.sin * y, self.sin * x + self.cos * y]
    }
}

/// A stretch of floor seen along a row: the world point of its first pixel and the step
/// from pixel to pixel, metres.
#[derive(Clone, Copy, Debug)]
pub struct FloorLine {
    pub start: [f64; 2],
    pub step: [f64; 2],
}

impl FloorTexture {
    /// Paints `out` (BGR pixels of one stretch of a row) with the floor along `line`,
    /// sampled by `code` (0 bilinear on the finest level, `1 + level` the nearest cell),
    /// every byte mapped through `tone`.
    pub fn paint_line(&self, code: u8, line: &FloorLine, tone: &[u8; 256], out: &mut [u8]) {
        let level = self.level_of(code);
        // Texel coordinates of the first pixel and the step, in fixed point.
        let fixed = |v: f64| (v * ONE).round() as i64;
        let inv = f64::from(level.inv_cell);
        let mut gx = fixed((line.start[0] - f64::from(self.x0)) * inv);
        let mut gy = fixed((line.start[1] - f64::from(self.y0)) * inv);
        let (dx, dy) = (fixed(line.step[0] * inv), fixed(line.step[1] * inv));
        let tone = |p: [u8; 3]| p.map(|v| tone[usize::from(v)]);
        let pixels = out.chunks_exact_mut(3);
        if code > 0 {
            for pixel in pixels {
                pixel.copy_from_slice(&tone(self.nearest(level, gx, gy)));
                gx += dx;
                gy += dy;
            }
            return;
        }
        // Neighbouring pixels of a magnified floor often fall between the same four
        // cells: those are fetched once.
        let mut cell = usize::MAX;
        let mut four = [0u64; 4];
        for pixel in pixels {
            let colour = match bilinear_place(level, gx, gy) {
                Some((i, ax, ay)) => {
                    if i != cell {
                        cell = i;
                        four = level.four_spread(i);
                    }
                    blend(&four, ax, ay)
                }
                None => self.outside,
            };
            pixel.copy_from_slice(&tone(colour));
            gx += dx;
            gy += dy;
        }
    }

    /// The cell of `l` at fixed-point texel coordinates (`gx`, `gy`).
    #[inline(always)]
    fn nearest(&self, l: &Level, gx: i64, gy: i64) -> [u8; 3] {
        let (ix, iy) = ((gx >> FRACTION) as usize, (gy >> FRACTION) as usize);
        if gx >= 0 && gy >= 0 && ix < l.width && iy < l.height {
            let [b, g, r, _] = l.texels[iy * l.width + ix];
            [b, g, r]
        } else {
            self.outside
        }
    }
}

/// Where fixed-point texel coordinates (`gx`, `gy`) fall among `l`'s cells for a
/// bilinear blend: the first of the four cells round them (texel centres at half cells)
/// and the weights past it along x and y in 1/256ths; None off the texture.
#[inline(always)]
fn bilinear_place(l: &Level, gx: i64, gy: i64) -> Option<(usize, u32, u32)> {
    if gx < 0 || gy < 0 {
        return None;
    }
    let half = 1i64 << (FRACTION - 1);
    let (fx, fy) = ((gx - half).max(0), (gy - half).max(0));
    let (ix, iy) = ((fx >> FRACTION) as usize, (fy >> FRACTION) as usize);
    if ix + 1 >= l.width || iy + 1 >= l.height {
        return None;
    }
    let weight = |f: i64| ((f >> (FRACTION - 8)) & 255) as u32;
    Some((iy * l.width + ix, weight(fx), weight(fy)))
}

impl Level {
    /// Cells `i`, `i + 1` and the two below them, each with its four bytes spread to
    /// 16-bit lanes of a `u64`.
    #[inline(always)]
    fn four_spread(&self, i: usize) -> [u64; 4] {
        let w = self.width;
        [i, i + 1, i + w, i + w + 1].map(|j| spread(u32::from_le_bytes(self.texels[j])))
    }
}

/// The four bytes of `x` in the four 16-bit lanes of a `u64`, lowest first.
#[inline(always)]
fn spread(x: u32) -> u64 {
    let x = u64::from(x);
    let x = (x | (x << 16)) & 0x0000_FFFF_0000_FFFF;
    (x | (x << 8)) & 0x00FF_00FF_00FF_00FF
}

/// The bilinear blend of four spread cells (top left, top right, bottom left, bottom
/// right) with weights `ax`, `ay` in 1/256ths, every channel in integer arithmetic:
/// ((p00 (256 - ax) + p10 ax) (256 - ay) + (p01 (256 - ax) + p11 ax) ay + 2^15) / 2^16.
/// The channels ride in the lanes of one word (SIMD within a register): the first
/// products stay under 2^16 (255 x 256), the second are taken in 32-bit lanes.
#[inline(always)]
fn blend(four: &[u64; 4], ax: u32, ay: u32) -> [u8; 3] {
    const EVEN: u64 = 0x0000_FFFF_0000_FFFF;
    const HALF: u64 = 0x0000_8000_0000_8000;
    let (ax, ay) = (u64::from(ax), u64::from(ay));
    let top = four[0] * (256 - ax) + four[1] * ax;
    let bottom = four[2] * (256 - ax) + four[3] * ax;
    let mix = |t: u64, b: u64| ((t * (256 - ay) + b * ay + HALF) >> 16) & 0x0000_00FF_0000_00FF;
    let br = mix(top & EVEN, bottom & EVEN);
    let g = mix((top >> 16) & EVEN, (bottom >> 16) & EVEN);
    [br as u8, g as u8, (br >> 32) as u8]
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    #[test]
    fn the_blend_in_lanes_is_the_blend_channel_by_channel() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        for _ in 0..100_000 {
            let p: [[u8; 4]; 4] = std::array::from_fn(|_| rng.random());
            let (ax, ay) = (rng.random_range(0..256u32), rng.random_range(0..256u32));
            // Edge weights and extreme bytes too.
            let (ax, ay) = if rng.random_bool(0.1) {
                (255, 0)
            } else {
                (ax, ay)
            };
            let four = p.map(|t| spread(u32::from_le_bytes(t)));
            let want = [0, 1, 2].map(|k| {
                let c = |i: usize| u32::from(p[i][k]);
                let top = c(0) * (256 - ax) + c(1) * ax;
                let bottom = c(2) * (256 - ax) + c(3) * ax;
                ((top * (256 - ay) + bottom * ay + 32768) >> 16) as u8
            });
            assert_eq!(blend(&four, ax, ay), want, "{p:?} {ax} {ay}");
        }
        let white = [u32::MAX; 4].map(spread);
        assert_eq!(blend(&white, 255, 255), [255; 3]);
    }
}
