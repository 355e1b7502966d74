//! The lane camera's sensor noise: zero-mean, about 3 grey levels of standard deviation on
//! every channel of every pixel. The offsets are drawn once, when the renderer is made,
//! into a bank a few frames long (`sim::noise_bank`).

pub use crate::sim::noise_bank::NoiseBank;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// Standard deviation of the noise, grey levels.
pub const NOISE_SD: f64 = 3.0;
/// Offsets in the bank: over four frames of 640x480 BGR.
const BANK: usize = 1 << 22;

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

/// The lane camera's bank, drawn from `rng`.
pub fn bank(rng: &mut ChaCha8Rng) -> NoiseBank {
    let table = table();
    let mut bytes = vec![0u8; BANK];
    rng.fill(&mut bytes[..]);
    NoiseBank::of(bytes.iter().map(|&b| table[usize::from(b)]).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn the_noise_is_centred_has_the_asked_spread_and_differs_from_frame_to_frame() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let bank = bank(&mut rng);
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
            let bank = bank(&mut rng);
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
