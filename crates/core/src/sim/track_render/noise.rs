//! The lane camera's sensor noise: zero-mean, about 3 grey levels of standard deviation on
//! every channel of every pixel, eight channels to each 64-bit draw of the generator. The
//! frame is shared among the cores, each part drawing from its own place in the
//! generator's stream, so the noise is the same however many cores there are.

use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

/// Standard deviation of the noise, grey levels.
pub const NOISE_SD: f64 = 3.0;
/// Bytes of one part of the frame (a whole number of draws).
const PART: usize = 8 * 8192;

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

/// Adds the noise to every byte of `pixels`, leaving `rng` past every draw taken.
pub fn add_noise(pixels: &mut [u8], rng: &mut ChaCha8Rng) {
    let table = table();
    // A 64-bit draw takes two 32-bit words of the ChaCha stream.
    let start = rng.get_word_pos();
    let stream = rng.clone();
    pixels
        .par_chunks_mut(PART)
        .enumerate()
        .for_each(|(k, part)| {
            let mut rng = stream.clone();
            rng.set_word_pos(start + 2 * (k * PART / 8) as u128);
            add_part(part, &mut rng, &table);
        });
    rng.set_word_pos(start + 2 * pixels.len().div_ceil(8) as u128);
}

fn add_part(pixels: &mut [u8], rng: &mut ChaCha8Rng, table: &[i16; 256]) {
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

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn the_noise_and_the_generator_after_it_are_those_of_one_part_drawn_in_order() {
        // Three parts and a remainder of five bytes.
        let len = 3 * PART + 5;
        let mut shared = vec![128u8; len];
        let mut one = shared.clone();
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let mut reference = rng.clone();
        add_noise(&mut shared, &mut rng);
        add_part(&mut one, &mut reference, &table());
        assert_eq!(shared, one);
        assert_eq!(rng.random::<u64>(), reference.random::<u64>());
        let spread = shared.iter().filter(|&&v| v != 128).count();
        assert!(spread > len / 2, "{spread} of {len} bytes moved");
    }
}
