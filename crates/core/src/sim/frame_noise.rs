//! The rendered camera's pixel noise: zero-mean, of a configured standard deviation,
//! drawn from the twin's generator four pixels to a 64-bit word, row after row.
//!
//! The noise of any pixel can be drawn alone: ChaCha's stream can be entered at any word
//! (`set_word_pos`), so the noise of a few regions of a frame is exactly what the whole
//! frame would have there, and the generator is left where the whole frame leaves it.

use crate::perception::region::Region;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// Pixels sharing one 64-bit draw.
const PER_DRAW: usize = 4;
/// ChaCha words (32 bits) in one 64-bit draw.
const WORDS_PER_DRAW: u128 = 2;

/// Grey-level offsets by the sum of two random bytes: the sum is triangular with variance
/// 2 * 256^2 / 12 (sum of independent uniforms), scaled to standard deviation `std`.
fn table(std: f64) -> Vec<i16> {
    let scale = std / (2.0f64 * 256.0 * 256.0 / 12.0).sqrt();
    (0..511)
        .map(|s| ((f64::from(s) - 255.0) * scale).round() as i16)
        .collect()
}

/// Adds the noise of the draw `bits` for pixel `k` of its four.
#[inline]
fn noisy(p: u8, bits: u64, k: usize, table: &[i16]) -> u8 {
    let a = (bits >> (16 * k)) as u8 as usize;
    let b = (bits >> (16 * k + 8)) as u8 as usize;
    (i16::from(p) + table[a + b]).clamp(0, 255) as u8
}

/// Adds zero-mean noise of standard deviation `std` to every pixel.
pub fn add_noise(pixels: &mut [u8], std: f64, rng: &mut ChaCha8Rng) {
    if std <= 0.0 {
        return;
    }
    let table = table(std);
    for chunk in pixels.chunks_mut(PER_DRAW) {
        let bits: u64 = rng.random();
        for (k, p) in chunk.iter_mut().enumerate() {
            *p = noisy(*p, bits, k, &table);
        }
    }
}

/// Adds to the pixels of `regions` (of a frame `width` pixels wide) the noise `add_noise`
/// would give them, and leaves `rng` where `add_noise` would leave it.
pub fn add_noise_in(
    pixels: &mut [u8],
    width: usize,
    regions: &[Region],
    std: f64,
    rng: &mut ChaCha8Rng,
) {
    if std <= 0.0 {
        return;
    }
    let table = table(std);
    let start = rng.get_word_pos();
    let at_draw = |draw: usize| start + WORDS_PER_DRAW * draw as u128;
    for r in regions {
        for y in r.y0..r.y1 {
            let (first, end) = (y * width + r.x0, y * width + r.x1);
            rng.set_word_pos(at_draw(first / PER_DRAW));
            let mut bits: u64 = rng.random();
            for (i, p) in pixels[first..end].iter_mut().enumerate() {
                let i = first + i;
                if i % PER_DRAW == 0 && i != first {
                    bits = rng.random();
                }
                *p = noisy(*p, bits, i % PER_DRAW, &table);
            }
        }
    }
    rng.set_word_pos(at_draw(pixels.len().div_ceil(PER_DRAW)));
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn noise_in_regions_is_the_whole_frames_noise_there() {
        // 13 pixels wide: rows do not start on a draw boundary.
        let (w, h) = (13, 9);
        let flat = vec![128u8; w * h];
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let mut whole = flat.clone();
        add_noise(&mut whole, 3.0, &mut rng);
        let after_whole: u64 = rng.random();

        let regions = [
            Region {
                x0: 1,
                y0: 2,
                x1: 6,
                y1: 5,
            },
            Region {
                x0: 9,
                y0: 0,
                x1: 13,
                y1: 9,
            },
        ];
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let mut part = flat.clone();
        add_noise_in(&mut part, w, &regions, 3.0, &mut rng);
        let after_part: u64 = rng.random();

        assert_eq!(after_whole, after_part, "the generator moved on alike");
        let inside = |x: usize, y: usize| {
            regions
                .iter()
                .any(|r| (r.x0..r.x1).contains(&x) && (r.y0..r.y1).contains(&y))
        };
        for y in 0..h {
            for x in 0..w {
                let i = y * w + x;
                let want = if inside(x, y) { whole[i] } else { flat[i] };
                assert_eq!(part[i], want, "pixel ({x}, {y})");
            }
        }
        assert_ne!(whole, flat, "there was noise to compare");
    }

    #[test]
    fn noise_has_the_configured_spread() {
        let mut pixels = vec![128u8; 100_000];
        add_noise(&mut pixels, 3.0, &mut ChaCha8Rng::seed_from_u64(1));
        let (mean, std) = crate::sim::noise_bank::spread(&pixels);
        assert!((mean - 128.0).abs() < 0.05, "mean {mean}");
        assert!((std - 3.0).abs() < 0.1, "std {std}");
    }
}
