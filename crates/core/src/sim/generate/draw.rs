//! Drawing round numbers from the seeded generator, so generated files read cleanly.

use crate::geometry::wrap_angle;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// A multiple of `step` in [lo, hi], uniformly; `None` when there is none.
pub fn pick(rng: &mut ChaCha8Rng, lo: f64, hi: f64, step: f64) -> Option<f64> {
    let first = (lo / step - 1e-9).ceil() as i64;
    let last = (hi / step + 1e-9).floor() as i64;
    (first <= last).then(|| tidy(rng.random_range(first..=last) as f64 * step))
}

/// A whole number of degrees, as radians in (-pi, pi].
pub fn heading(rng: &mut ChaCha8Rng) -> f64 {
    wrap_angle(f64::from(rng.random_range(-179i32..=180)).to_radians())
}

/// `v` to 9 decimals, so that 7 x 0.05 reads 0.35 and not 0.35000000000000003.
pub fn tidy(v: f64) -> f64 {
    format!("{v:.9}").parse().unwrap_or(v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn picks_are_round_and_inside() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        for _ in 0..200 {
            let v = pick(&mut rng, -1.23, 0.4, 0.05).unwrap();
            assert!((-1.23..=0.4).contains(&v), "{v}");
            assert_eq!(v, tidy((v / 0.05).round() * 0.05));
        }
        assert_eq!(pick(&mut rng, 0.31, 0.34, 0.05), None);
        assert_eq!(pick(&mut rng, 0.35, 0.35, 0.05), Some(0.35));
    }
}
