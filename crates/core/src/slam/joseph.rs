//! The Joseph-form covariance update for one two-dimensional sighting, in O(n^2) on the
//! stored lower triangle of a symmetric covariance.

use nalgebra::{DMatrix, Matrix2};

/// A Kalman gain for one two-dimensional sighting: N x 2.
pub type Gain = nalgebra::OMatrix<f64, nalgebra::Dyn, nalgebra::U2>;

/// Sigma <- Sigma - K U^T - U K^T + K S K^T for N x 2 matrices K and U, on the lower
/// triangle, one pass over the columns. With A = K S - U the same matrix is
/// Sigma - K U^T + A K^T (since K S K^T = U K^T + A K^T), which reads four columns per
/// element instead of six.
pub fn joseph_update(sigma: &mut DMatrix<f64>, k: &Gain, u: &DMatrix<f64>, s: &Matrix2<f64>) {
    let n = sigma.nrows();
    let a = k * s - u;
    let (k0, k1) = (k.column(0), k.column(1));
    let (a0, a1) = (a.column(0), a.column(1));
    let (u0, u1) = (u.column(0), u.column(1));
    let (k0, k1, a0, a1) = (k0.as_slice(), k1.as_slice(), a0.as_slice(), a1.as_slice());
    let (u0, u1) = (u0.as_slice(), u1.as_slice());
    for (c, column) in sigma.as_mut_slice().chunks_exact_mut(n).enumerate() {
        let (kc0, kc1, uc0, uc1) = (k0[c], k1[c], u0[c], u1[c]);
        let rows = k0[c..]
            .iter()
            .zip(&k1[c..])
            .zip(a0[c..].iter().zip(&a1[c..]));
        for (v, ((ki0, ki1), (ai0, ai1))) in column[c..].iter_mut().zip(rows) {
            *v += ai0 * kc0 + ai1 * kc1 - (ki0 * uc0 + ki1 * uc1);
        }
    }
}
