//! Confidence ellipses of 2D Gaussians, for drawing what the filter believes.

use crate::geometry::Point2;
use nalgebra::Matrix2;

/// Chi-square with 2 degrees of freedom at 95 %: the ellipse holding 95 % of the mass.
pub const CHI2_2DOF_95: f64 = 5.991;

/// Semi-axes (major, minor) and the major axis' angle of the `chi2` ellipse of `cov`
/// (eigen-decomposition of a symmetric 2x2 matrix in closed form).
pub fn axes(cov: &Matrix2<f64>, chi2: f64) -> (f64, f64, f64) {
    let (a, b, c) = (cov[(0, 0)], 0.5 * (cov[(0, 1)] + cov[(1, 0)]), cov[(1, 1)]);
    let mid = 0.5 * (a + c);
    let rad = (0.25 * (a - c) * (a - c) + b * b).sqrt();
    let (l1, l2) = ((mid + rad).max(0.0), (mid - rad).max(0.0));
    let angle = 0.5 * (2.0 * b).atan2(a - c);
    ((chi2 * l1).sqrt(), (chi2 * l2).sqrt(), angle)
}

/// `n` points on the `chi2` ellipse of `cov` around `center`.
pub fn outline(center: Point2, cov: &Matrix2<f64>, chi2: f64, n: usize) -> Vec<Point2> {
    let (major, minor, angle) = axes(cov, chi2);
    let (s, c) = angle.sin_cos();
    (0..n)
        .map(|i| {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            let (u, v) = (major * t.cos(), minor * t.sin());
            Point2::new(center.x + c * u - s * v, center.y + s * u + c * v)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axis_aligned_ellipse() {
        let (major, minor, angle) = axes(&Matrix2::new(4.0, 0.0, 0.0, 1.0), CHI2_2DOF_95);
        assert!((major - 2.0 * CHI2_2DOF_95.sqrt()).abs() < 1e-12);
        assert!((minor - CHI2_2DOF_95.sqrt()).abs() < 1e-12);
        assert!(angle.abs() < 1e-12);
    }

    #[test]
    fn correlated_ellipse_leans_on_the_diagonal() {
        let (_, _, angle) = axes(&Matrix2::new(1.0, 0.9, 0.9, 1.0), 1.0);
        assert!((angle - std::f64::consts::FRAC_PI_4).abs() < 1e-12);
        let pts = outline(
            Point2::new(1.0, 1.0),
            &Matrix2::new(1.0, 0.0, 0.0, 1.0),
            1.0,
            4,
        );
        assert!((pts[0].x - 2.0).abs() < 1e-12 && (pts[1].y - 2.0).abs() < 1e-12);
    }
}
