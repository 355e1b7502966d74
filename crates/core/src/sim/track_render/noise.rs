//! The lane camera's sensor noise: zero-mean, about 3 grey levels of standard deviation on
//! every channel of every pixel. The offsets are drawn once, when the renderer is made,
//! into a bank a few frames long; each frame adds the bank from a place the caller's
//! generator draws, so frames differ and a frame costs one pass of additions.

use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

/// Standard deviation of the noise, grey levels.
pub const NOISE_SD: f64 = 3.0;
/// Offsets in the bank: over four frames of 640x480 BGR.
const BANK: usize = 1 << 22;
/// Bytes a core takes at a time.
const PART: usize = 1 << 18;

/// Offsets by the byte drawn: the sum of its two 4-bit halves is triangular on 0..=30
/// with variance 2 (16^2 - 1) / 12 = 42.5 (sum of independent discrete uniforms), centred
/// and scaled to `NOISE_SD`.
fn table() -> [i8; 256] {
    let scale = NOISE_SD / 42.5f64.sqrt();
    std::array::from_fn(|b| {
        let sum = (b & 15) + (b >> 4);
        ((sum as f64 - 15.0) * scale).round() as i8
    })
}

/// Noise offsets drawn once and added to frame after frame from a drawn place.
#[derive(Clone)]
pub struct NoiseBank {
    offsets: Vec<i8>,
}

impl std::fmt::Debug for NoiseBank {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "NoiseBank {{ {} offsets }}", self.offsets.len())
    }
}

impl NoiseBank {
    /// A bank drawn from `rng`.
    pub fn new(rng: &mut ChaCha8Rng) -> Self {
        let table = table();
        let mut bytes = vec![0u8; BANK];
        rng.fill(&mut bytes[..]);
        Self {
            offsets: bytes.iter().map(|&b| table[usize::from(b)]).collect(),
        }
    }

    /// Adds the noise to every byte of `pixels`, from a place in the bank drawn from `rng`
    /// (wrapping round its end).
    pub fn add(&self, pixels: &mut [u8], rng: &mut ChaCha8Rng) {
        let mut at = rng.random_range(0..self.offsets.len());
        for part in pixels.chunks_mut(self.offsets.len()) {
            let (head, tail) = part.split_at_mut(part.len().min(self.offsets.len() - at));
            add_offsets(head, &self.offsets[at..]);
            add_offsets(tail, &self.offsets);
            at = (at + part.len()) % self.offsets.len();
        }
    }
}

/// `pixels[i] += offsets[i]`, held to 0..=255, a share of the pixels to each core.
fn add_offsets(pixels: &mut [u8], offsets: &[i8]) {
    let n = pixels.len().min(offsets.len());
    (pixels[..n].par_chunks_mut(PART))
        .zip(offsets[..n].par_chunks(PART))
        .for_each(|(pixels, offsets)| {
            for (p, &o) in pixels.iter_mut().zip(offsets) {
                *p = (i16::from(*p) + i16::from(o)).clamp(0, 255) as u8;
            }
        });
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn the_noise_is_centred_has_the_asked_spread_and_differs_from_frame_to_frame() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let bank = NoiseBank::new(&mut rng);
        let frame = || vec![128u8; 3 * 640 * 480];
        let (mut a, mut b) = (frame(), frame());
        bank.add(&mut a, &mut rng);
        bank.add(&mut b, &mut rng);
        let n = a.len() as f64;
        let mean = a.iter().map(|&v| f64::from(v) - 128.0).sum::<f64>() / n;
        let sd = (a
            .iter()
            .map(|&v| (f64::from(v) - 128.0).powi(2))
            .sum::<f64>()
            / n)
            .sqrt();
        assert!(mean.abs() < 0.05, "mean {mean}");
        assert!((sd - NOISE_SD).abs() < 0.15, "sd {sd}");
        let same = a.iter().zip(&b).filter(|(p, q)| p == q).count();
        assert!(same < a.len() / 4, "{same} of {} bytes alike", a.len());
    }

    #[test]
    fn the_same_generator_gives_the_same_noise_and_extremes_stay_in_range() {
        let noisy = |fill: u8| {
            let mut rng = ChaCha8Rng::seed_from_u64(3);
            let bank = NoiseBank::new(&mut rng);
            // Longer than the bank: it wraps.
            let mut pixels = vec![fill; BANK + 1000];
            bank.add(&mut pixels, &mut rng);
            pixels
        };
        assert_eq!(noisy(128), noisy(128));
        assert!(noisy(0).iter().any(|&v| v > 0));
        assert!(noisy(255).iter().any(|&v| v < 255));
    }
}
