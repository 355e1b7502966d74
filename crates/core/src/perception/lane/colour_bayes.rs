//! The traffic light's colour from a lamp's hue: seed 000 §3.1.2's Bayesian classifier
//! over §3.1.1's hue distributions, with yellow added.

use crate::data::LightColour;

/// A normal density N(h; mu, sigma) (seed 000 §3.1.1).
fn normal(h: f64, mu: f64, sigma: f64) -> f64 {
    let z = (h - mu) / sigma;
    (-0.5 * z * z).exp() / ((2.0 * std::f64::consts::PI).sqrt() * sigma)
}

/// seed 000 §3.1.1: red's wrapped density, peaks at 10 and 170, sigma 8 (OpenCV hue units).
fn red(h: f64) -> f64 {
    normal(h, 10.0, 8.0) + normal(h, 170.0, 8.0)
}

/// seed 000 §3.1.1: green, mu 65, sigma 12.
fn green(h: f64) -> f64 {
    normal(h, 65.0, 12.0)
}

/// Not in the seed: a yellow lamp's hue, mu 28, sigma 6 (amber to yellow, 22-34 within one
/// sigma; clear of red's 10 by three sigma of red's and yellow's together).
fn yellow(h: f64) -> f64 {
    normal(h, 28.0, 6.0)
}

/// Not a lamp: any hue alike over OpenCV's 0-180.
fn none(_h: f64) -> f64 {
    1.0 / 180.0
}

/// Priors red, yellow, green, none. seed 000 §3.1.2 gives red 0.4, green 0.4, none 0.2
/// without yellow; yellow shows for a fraction of red's and green's time, so 0.05 of each
/// of theirs is given to it: 0.35, 0.1, 0.35, 0.2.
pub const PRIORS: [f64; 4] = [0.35, 0.1, 0.35, 0.2];

/// The posterior of red, yellow, green and none for hue `h` (0-180).
pub fn posterior(h: f64) -> [f64; 4] {
    let likelihood = [red(h), yellow(h), green(h), none(h)];
    // seed 000 §3.1.2: P(class | h) = p(h | class) P(class) / sum over classes.
    let joint: Vec<f64> = likelihood.iter().zip(PRIORS).map(|(l, p)| l * p).collect();
    let total: f64 = joint.iter().sum();
    [0, 1, 2, 3].map(|i| joint[i] / total)
}

/// The most probable lamp colour for hue `h` and its posterior, none when "not a lamp"
/// is the most probable.
pub fn classify(h: f64) -> Option<(LightColour, f64)> {
    let p = posterior(h);
    let best = (0..4).max_by(|&a, &b| p[a].total_cmp(&p[b]))?;
    (best < 3).then(|| (COLOURS[best], p[best]))
}

/// The lamp colours in the order `posterior` gives them.
const COLOURS: [LightColour; 3] = [LightColour::Red, LightColour::Yellow, LightColour::Green];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hues_are_read_as_the_lamp_colours_and_blue_as_none() {
        assert_eq!(classify(2.0).map(|c| c.0), Some(LightColour::Red));
        assert_eq!(classify(176.0).map(|c| c.0), Some(LightColour::Red));
        assert_eq!(classify(29.0).map(|c| c.0), Some(LightColour::Yellow));
        assert_eq!(classify(63.0).map(|c| c.0), Some(LightColour::Green));
        assert_eq!(classify(120.0), None);
        // At green's peak: 0.35 N(0; 12) against 0.2 / 180 and a whisker of yellow.
        let p = posterior(65.0);
        let g = 0.35 * normal(65.0, 65.0, 12.0);
        let expect = g / (g + 0.35 * red(65.0) + 0.1 * yellow(65.0) + 0.2 / 180.0);
        assert!((p[2] - expect).abs() < 1e-12 && p[2] > 0.9, "{p:?}");
    }
}
