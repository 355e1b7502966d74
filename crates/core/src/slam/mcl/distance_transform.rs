//! The exact Euclidean distance transform MCL's map is measured with.

/// Squared distance (in cells) from each cell to the nearest `true` cell: the exact
/// Euclidean transform of Felzenszwalb and Huttenlocher, "Distance Transforms of Sampled
/// Functions" (2012), one pass over columns and one over rows.
pub fn squared_distance_transform(seeds: &[bool], width: usize, height: usize) -> Vec<f64> {
    let far = ((width * width + height * height) as f64) * 4.0 + 1.0;
    let mut out: Vec<f64> = seeds.iter().map(|&s| if s { 0.0 } else { far }).collect();
    let n = width.max(height);
    let (mut f, mut d) = (vec![0.0; n], vec![0.0; n]);
    let (mut v, mut z) = (vec![0usize; n], vec![0.0; n + 1]);
    for x in 0..width {
        for y in 0..height {
            f[y] = out[y * width + x];
        }
        envelope(&f[..height], &mut d[..height], &mut v, &mut z);
        for y in 0..height {
            out[y * width + x] = d[y];
        }
    }
    for y in 0..height {
        let row = &mut out[y * width..(y + 1) * width];
        f[..width].copy_from_slice(row);
        envelope(&f[..width], &mut d[..width], &mut v, &mut z);
        row.copy_from_slice(&d[..width]);
    }
    out
}

/// One dimension of the transform: the lower envelope of the parabolas (q - p)² + f(p)
/// (Felzenszwalb and Huttenlocher 2012, algorithm DT(f)).
fn envelope(f: &[f64], d: &mut [f64], v: &mut [usize], z: &mut [f64]) {
    let n = f.len();
    if n == 0 {
        return;
    }
    let mut k = 0;
    v[0] = 0;
    z[0] = f64::NEG_INFINITY;
    z[1] = f64::INFINITY;
    for q in 1..n {
        loop {
            let p = v[k];
            // Where the parabola from q meets the one from p.
            let s = ((f[q] + (q * q) as f64) - (f[p] + (p * p) as f64)) / (2.0 * (q - p) as f64);
            if s <= z[k] && k > 0 {
                k -= 1;
                continue;
            }
            if s <= z[k] {
                // k == 0 and q's parabola is lower everywhere to the right of -inf.
                v[0] = q;
                z[1] = f64::INFINITY;
                break;
            }
            k += 1;
            v[k] = q;
            z[k] = s;
            z[k + 1] = f64::INFINITY;
            break;
        }
    }
    k = 0;
    for (q, out) in d.iter_mut().enumerate().take(n) {
        while z[k + 1] < q as f64 {
            k += 1;
        }
        let p = v[k];
        let dq = q as f64 - p as f64;
        *out = dq * dq + f[p];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn brute(seeds: &[bool], w: usize, h: usize) -> Vec<f64> {
        (0..w * h)
            .map(|i| {
                let (x, y) = ((i % w) as f64, (i / w) as f64);
                (0..w * h)
                    .filter(|&j| seeds[j])
                    .map(|j| {
                        let (a, b) = ((j % w) as f64, (j / w) as f64);
                        (x - a).powi(2) + (y - b).powi(2)
                    })
                    .fold(f64::INFINITY, f64::min)
            })
            .collect()
    }

    #[test]
    fn the_transform_matches_brute_force() {
        let (w, h) = (13, 9);
        let mut seeds = vec![false; w * h];
        for &i in &[0, 17, 40, 41, 88, 116] {
            seeds[i] = true;
        }
        assert_eq!(
            squared_distance_transform(&seeds, w, h),
            brute(&seeds, w, h)
        );
    }
}
