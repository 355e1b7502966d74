//! The EKF's covariance update for one two-dimensional sighting, in O(n^2) on the stored
//! lower triangle of a symmetric covariance, touching each stored element once.

use nalgebra::{DMatrix, Matrix2};

/// The factor W = U L^-T of one sighting's update, where U = P H^T (N x 2) and
/// S = L L^T (`l`, lower) is the Cholesky factor of the innovation covariance: with the
/// optimal gain K = U S^-1, (I - K H) P = P - U S^-1 U^T = P - W W^T (Bar-Shalom et al.
/// 5.2.3), a symmetric downdate by construction. Overwrites `u0`, `u1` with W's columns.
pub fn into_downdate_factor(u0: &mut [f64], u1: &mut [f64], l: &Matrix2<f64>) {
    let (l00, l10, l11) = (l[(0, 0)], l[(1, 0)], l[(1, 1)]);
    // Row i of W solves L w_i = u_i by forward substitution.
    for (a, b) in u0.iter_mut().zip(u1.iter_mut()) {
        *a /= l00;
        *b = (*b - l10 * *a) / l11;
    }
}

/// Sigma <- Sigma - W W^T on the lower triangle, one pass over the columns: each stored
/// element is read and written once, with two multiply-adds.
pub fn symmetric_downdate(sigma: &mut DMatrix<f64>, w0: &[f64], w1: &[f64]) {
    let n = sigma.nrows();
    for (c, column) in sigma.as_mut_slice().chunks_exact_mut(n).enumerate() {
        let (a, b) = (w0[c], w1[c]);
        for ((v, x0), x1) in column[c..].iter_mut().zip(&w0[c..]).zip(&w1[c..]) {
            *v -= x0 * a + x1 * b;
        }
    }
}
