//! The lane camera's sensor noise: zero-mean, about 3 grey levels of standard deviation on
//! every channel of every pixel, eight channels to each 64-bit draw of the generator.

use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// Standard deviation of the noise, grey levels.
pub const NOISE_SD: f64 = 3.0;

/// Offsets by the byte drawn: the sum of its two 4-bit halves is triangular on 0..=30
/// with variance 2 (16^2 - 1) / 12 = 42.5 (sum of independent discrete uniforms), centred
/// and scaled to `NOISE_SD`.
fn table() -> [i16; 256] {
    let scale = NOISE_SD / 42.5f64.sqrt();
    std::array::from_fn(|b| {
        let sum = (b & 15) + (b >> 4);
        ((sum as f64 - 15.0) * scale).round() as i16
    })
}

/// Adds the noise to every byte of `pixels`.
pub fn add_noise(pixels: &mut [u8], rng: &mut ChaCha8Rng) {
    let table = table();
    let mut chunks = pixels.chunks_exact_mut(8);
    for chunk in &mut chunks {
        let bytes = rng.random::<u64>().to_le_bytes();
        for (p, b) in chunk.iter_mut().zip(bytes) {
            *p = (i16::from(*p) + table[usize::from(b)]).clamp(0, 255) as u8;
        }
    }
    let rest = chunks.into_remainder();
    if !rest.is_empty() {
        let bytes = rng.random::<u64>().to_le_bytes();
        for (p, b) in rest.iter_mut().zip(bytes) {
            *p = (i16::from(*p) + table[usize::from(b)]).clamp(0, 255) as u8;
        }
    }
}
