//! Clamped uniform B-splines: evaluation by de Boor's algorithm and derivative curves
//! (Piegl & Tiller, "The NURBS Book", 2nd ed., sections 2.2, 3.3 and eq. 3.8).

/// A planar B-spline curve.
#[derive(Clone, Debug, PartialEq)]
pub struct BSpline {
    pub degree: usize,
    pub knots: Vec<f64>,
    pub control: Vec<[f64; 2]>,
}

impl BSpline {
    /// A clamped uniform curve through the first and last control points: knots
    /// 0 (degree + 1 times), 1, 2, ..., m - degree (degree + 1 times). Needs more control
    /// points than the degree.
    pub fn clamped(degree: usize, control: Vec<[f64; 2]>) -> Self {
        let m = control.len();
        assert!(
            m > degree,
            "a degree-{degree} B-spline needs {} control points",
            degree + 1
        );
        let last = (m - degree) as f64;
        let knots = (0..m + degree + 1)
            .map(|i| (i.saturating_sub(degree) as f64).min(last))
            .collect();
        Self {
            degree,
            knots,
            control,
        }
    }

    /// The parameter range.
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[self.degree], self.knots[self.control.len()])
    }

    /// The point at parameter `u` by de Boor's triangular scheme (de Boor 1972); the result
    /// equals The NURBS Book A3.1, which goes through the basis functions.
    pub fn eval(&self, u: f64) -> [f64; 2] {
        let p = self.degree;
        let n = self.control.len();
        let (lo, hi) = self.domain();
        let u = u.clamp(lo, hi);
        // The knot span k with knots[k] <= u < knots[k + 1], the last one at u = hi.
        let k = if u >= hi {
            n - 1
        } else {
            self.knots[..=n].partition_point(|&t| t <= u) - 1
        };
        let mut d: Vec<[f64; 2]> = self.control[k - p..=k].to_vec();
        for r in 1..=p {
            for j in (r..=p).rev() {
                let left = self.knots[j + k - p];
                let right = self.knots[j + 1 + k - r];
                let alpha = if right > left {
                    (u - left) / (right - left)
                } else {
                    0.0
                };
                d[j] = [
                    (1.0 - alpha) * d[j - 1][0] + alpha * d[j][0],
                    (1.0 - alpha) * d[j - 1][1] + alpha * d[j][1],
                ];
            }
        }
        d[p]
    }

    /// The derivative curve: degree p - 1 with control points
    /// Q_i = p (P_{i+1} - P_i) / (u_{i+p+1} - u_{i+1}) (The NURBS Book eq. 3.8).
    pub fn derivative(&self) -> Self {
        let p = self.degree;
        assert!(p >= 1, "a constant curve has no derivative curve here");
        let control = self
            .control
            .windows(2)
            .enumerate()
            .map(|(i, w)| {
                let span = self.knots[i + p + 1] - self.knots[i + 1];
                let f = if span > 0.0 { p as f64 / span } else { 0.0 };
                [f * (w[1][0] - w[0][0]), f * (w[1][1] - w[0][1])]
            })
            .collect();
        Self {
            degree: p - 1,
            knots: self.knots[1..self.knots.len() - 1].to_vec(),
            control,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_clamped_cubic_starts_and_ends_on_its_end_controls() {
        let c = vec![[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0], [5.0, 1.0]];
        let s = BSpline::clamped(3, c);
        let (lo, hi) = s.domain();
        assert_eq!(s.eval(lo), [0.0, 0.0]);
        assert_eq!(s.eval(hi), [5.0, 1.0]);
    }

    #[test]
    fn the_derivative_matches_a_finite_difference() {
        let c = vec![[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0], [5.0, 1.0]];
        let s = BSpline::clamped(3, c);
        let d = s.derivative();
        for u in [0.3, 1.0, 1.7] {
            let h = 1e-6;
            let (a, b) = (s.eval(u - h), s.eval(u + h));
            let fd = [(b[0] - a[0]) / (2.0 * h), (b[1] - a[1]) / (2.0 * h)];
            let an = d.eval(u);
            assert!((fd[0] - an[0]).abs() < 1e-5 && (fd[1] - an[1]).abs() < 1e-5);
        }
    }
}
