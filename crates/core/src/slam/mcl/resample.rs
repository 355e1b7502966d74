//! Resampling: the low-variance sampler (Probabilistic Robotics table 4.4), the effective
//! sample size that decides when to resample (4.3.4), and the KLD bound on how many
//! particles the belief needs (table 8.4, Fox 2003).

use rand::Rng;

/// Indices of `count` particles drawn in proportion to `weights` (normalised): one random
/// offset, then a comb of equal steps (table 4.4). A particle of weight w is drawn
/// ⌊w·count⌋ or ⌈w·count⌉ times, never by luck more or less.
pub fn low_variance(weights: &[f64], count: usize, rng: &mut impl Rng) -> Vec<usize> {
    let mut picked = Vec::with_capacity(count);
    if weights.is_empty() || count == 0 {
        return picked;
    }
    let step = 1.0 / count as f64;
    let r = rng.random::<f64>() * step;
    let (mut i, mut cumulative) = (0, weights[0]);
    for m in 0..count {
        let u = r + m as f64 * step;
        while u > cumulative && i + 1 < weights.len() {
            i += 1;
            cumulative += weights[i];
        }
        picked.push(i);
    }
    picked
}

/// The effective sample size of normalised weights, 1 / Σ w² (Probabilistic Robotics 4.3.4;
/// Liu 1996).
pub fn effective_sample_size(weights: &[f64]) -> f64 {
    let sum_sq: f64 = weights.iter().map(|w| w * w).sum();
    if sum_sq > 0.0 { 1.0 / sum_sq } else { 0.0 }
}

/// How many particles keep the KL divergence between the sampled and the true belief under
/// `err` with probability 1 - δ, when the samples fall into `bins` histogram bins
/// (table 8.4, line 15): (k-1)/(2ε) · {1 - 2/(9(k-1)) + √(2/(9(k-1))) z}³.
pub fn kld_bound(bins: usize, err: f64, z: f64) -> usize {
    if bins <= 1 {
        return 1;
    }
    let k = (bins - 1) as f64;
    let b = 2.0 / (9.0 * k);
    let x = 1.0 - b + b.sqrt() * z;
    (k / (2.0 * err) * x * x * x).ceil() as usize
}

/// The power β in (0, 1] of the scan's likelihood that keeps the effective sample size of
/// `prior` · p^β at least `keep` of the prior's own: the largest such, 1 when the whole
/// likelihood keeps that many. The annealed particle filter's rule (Deutscher, Blake and
/// Reid 2000: each layer's exponent chosen for a survival rate, 0.5 there): sixty beams
/// taken as independent make one scan's likelihood so sharp that a global localisation
/// would keep the one particle that happened to land nearest a look-alike pose; tempered,
/// a scan trims the hypotheses by half and the next scans, from elsewhere, decide.
pub fn tempering(prior: &[f64], logs: &[f64], top: f64, keep: f64) -> f64 {
    // Of weights not normalised: (Σ w)² / Σ w² (Probabilistic Robotics 4.3.4).
    let ess = |beta: f64| {
        let (mut sum, mut sum_sq) = (0.0, 0.0);
        for (p, l) in prior.iter().zip(logs) {
            let w = p * (beta * (l - top)).exp();
            sum += w;
            sum_sq += w * w;
        }
        if sum_sq > 0.0 {
            sum * sum / sum_sq
        } else {
            0.0
        }
    };
    let want = keep * ess(0.0);
    if ess(1.0) >= want {
        return 1.0;
    }
    // Bisection: the effective sample size falls as the power grows.
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..30 {
        let mid = 0.5 * (lo + hi);
        if ess(mid) >= want { lo = mid } else { hi = mid }
    }
    lo
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    #[test]
    fn tempering_keeps_half_the_effective_sample_size() {
        // Four even particles, log-likelihoods 0, -2, -4, -6: the whole likelihood leaves
        // an effective size of (1 + e^-2 + e^-4 + e^-6)² / (1 + e^-4 + e^-8 + e^-12) = 1.31,
        // under half of 4, so a power under 1 keeps exactly 2.
        let prior = [0.25; 4];
        let logs = [0.0, -2.0, -4.0, -6.0];
        let beta = tempering(&prior, &logs, 0.0, 0.5);
        assert!(beta > 0.0 && beta < 1.0, "{beta}");
        let w: Vec<f64> = logs.iter().map(|l| (beta * l).exp()).collect();
        let ess = w.iter().sum::<f64>().powi(2) / w.iter().map(|x| x * x).sum::<f64>();
        assert!((ess - 2.0).abs() < 1e-6, "{ess}");
        // Likelihoods that keep enough are taken whole.
        assert_eq!(tempering(&prior, &[0.0, -0.1, -0.1, 0.0], 0.0, 0.5), 1.0);
    }

    #[test]
    fn the_kld_bound_against_hand_worked_values() {
        // k = 2: (1/0.1) · (1 - 2/9 + √(2/9) · 2.326)³ = 65.84 -> 66.
        assert_eq!(kld_bound(2, 0.05, 2.326), 66);
        // k = 101: 1000 · (1 - 2/900 + √(2/900) · 2.326)³ = 1358.14 -> 1359.
        assert_eq!(kld_bound(101, 0.05, 2.326), 1359);
        assert_eq!(kld_bound(1, 0.05, 2.326), 1);
    }

    #[test]
    fn effective_sample_size_of_even_and_lopsided_weights() {
        assert!((effective_sample_size(&[0.25; 4]) - 4.0).abs() < 1e-12);
        assert!((effective_sample_size(&[1.0, 0.0, 0.0]) - 1.0).abs() < 1e-12);
        // 1 / (0.5² + 0.25² + 0.25²) = 1 / 0.375.
        let ess = effective_sample_size(&[0.5, 0.25, 0.25]);
        assert!((ess - 1.0 / 0.375).abs() < 1e-12);
    }

    #[test]
    fn low_variance_draws_each_particle_as_often_as_its_weight_says() {
        let weights = [0.5, 0.3, 0.15, 0.05];
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        for _ in 0..100 {
            let picked = low_variance(&weights, 20, &mut rng);
            let count = |i| picked.iter().filter(|&&p| p == i).count();
            // Exactly w · 20 for these weights: 10, 6, 3, 1, whatever the offset.
            assert_eq!([count(0), count(1), count(2), count(3)], [10, 6, 3, 1]);
        }
    }

    #[test]
    fn resampling_keeps_the_distribution() {
        // 1000 particles on a line with Gaussian weights around 2: after resampling, the
        // unweighted mean and spread are the weighted ones (a fixed seed, tolerances of
        // several standard errors).
        let xs: Vec<f64> = (0..1000).map(|i| i as f64 * 0.004).collect();
        let raw: Vec<f64> = xs
            .iter()
            .map(|x| (-(x - 2.0f64).powi(2) / 0.08).exp())
            .collect();
        let total: f64 = raw.iter().sum();
        let w: Vec<f64> = raw.iter().map(|r| r / total).collect();
        let mean: f64 = xs.iter().zip(&w).map(|(x, w)| x * w).sum();
        let var: f64 = xs.iter().zip(&w).map(|(x, w)| w * (x - mean).powi(2)).sum();
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let picked = low_variance(&w, 1000, &mut rng);
        let ys: Vec<f64> = picked.iter().map(|&i| xs[i]).collect();
        let m2 = ys.iter().sum::<f64>() / 1000.0;
        let v2 = ys.iter().map(|y| (y - m2).powi(2)).sum::<f64>() / 1000.0;
        assert!(
            (m2 - 2.0).abs() < 0.005 && (mean - 2.0).abs() < 1e-6,
            "{m2}"
        );
        assert!(
            (v2.sqrt() - var.sqrt()).abs() < 0.005,
            "{} vs {}",
            v2.sqrt(),
            var.sqrt()
        );
        // A χ² test of the counts in 10 bins against the weights: 9 degrees of freedom,
        // 21.67 is the 99 % point.
        let mut chi2 = 0.0;
        for b in 0..10 {
            let lo = 1.5 + b as f64 * 0.1;
            let expected: f64 = (xs.iter().zip(&w))
                .filter(|(x, _)| (lo..lo + 0.1).contains(*x))
                .map(|(_, w)| w * 1000.0)
                .sum();
            let seen = ys.iter().filter(|y| (lo..lo + 0.1).contains(*y)).count() as f64;
            chi2 += (seen - expected).powi(2) / expected;
        }
        assert!(chi2 < 21.67, "χ² = {chi2}");
    }
}
