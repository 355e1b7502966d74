//! Sensor noise drawn once and added frame after frame: a bank of grey-level offsets,
//! each frame adding it from a place the caller's generator draws (wrapping round its
//! end), so frames differ and a frame costs one pass of additions. The rendered cameras
//! each draw their own bank (`track_render::noise` for the lane camera, `tag_render`'s
//! floor for the tag camera).

use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

/// Bytes a core takes at a time.
const PART: usize = 1 << 18;

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
    /// A bank of `offsets` (at least one).
    pub fn of(offsets: Vec<i8>) -> Self {
        let offsets = if offsets.is_empty() { vec![0] } else { offsets };
        Self { offsets }
    }

    /// How many offsets the bank holds.
    pub fn len(&self) -> usize {
        self.offsets.len()
    }

    pub fn is_empty(&self) -> bool {
        self.offsets.is_empty()
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

/// The mean and standard deviation of `pixels`' grey levels, for the noise tests.
#[cfg(test)]
pub(crate) fn spread(pixels: &[u8]) -> (f64, f64) {
    let n = pixels.len() as f64;
    let mean = pixels.iter().map(|&p| f64::from(p)).sum::<f64>() / n;
    let var = (pixels.iter())
        .map(|&p| (f64::from(p) - mean).powi(2))
        .sum::<f64>()
        / n;
    (mean, var.sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn a_frame_longer_than_the_bank_wraps_as_adding_one_byte_at_a_time_would() {
        let offsets: Vec<i8> = (0..1000).map(|k| ((k * 37) % 21) as i8 - 10).collect();
        let bank = NoiseBank::of(offsets.clone());
        let mut pixels: Vec<u8> = (0..2600).map(|k| (k % 256) as u8).collect();
        let mut want = pixels.clone();
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let at = rng.clone().random_range(0..offsets.len());
        for (k, p) in want.iter_mut().enumerate() {
            let o = offsets[(at + k) % offsets.len()];
            *p = (i16::from(*p) + i16::from(o)).clamp(0, 255) as u8;
        }
        bank.add(&mut pixels, &mut rng);
        assert_eq!(pixels, want);
    }
}
