//! The pose graph: keyframe poses as nodes, what scan matching measured between them as
//! edges, and the sparse least-squares solve that makes them agree (Grisetti, Kümmerle,
//! Stachniss and Burgard, "A Tutorial on Graph-Based SLAM", 2010; Konolige et al.,
//! "Efficient Sparse Pose Adjustment for 2D Mapping", 2010, which slam_toolbox's solver
//! follows).

use crate::geometry::{Pose2, wrap_angle};
use nalgebra::{DVector, Matrix3, Vector3};
use nalgebra_sparse::factorization::CscCholesky;
use nalgebra_sparse::{CooMatrix, CscMatrix};

/// What an edge was measured by.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum EdgeKind {
    /// A keyframe matched against the local map of the ones before it.
    Sequential,
    /// A keyframe matched against an older part of the map the robot came back to.
    Loop,
}

/// A measured pose of node `to` in the frame of node `from`, with its information
/// (inverse covariance).
#[derive(Clone, Debug, PartialEq)]
pub struct Edge {
    pub from: usize,
    pub to: usize,
    pub relative: Pose2,
    pub information: Matrix3<f64>,
    pub kind: EdgeKind,
}

/// Nodes' poses and the edges between them.
#[derive(Clone, Debug, Default)]
pub struct PoseGraph {
    pub poses: Vec<Pose2>,
    pub edges: Vec<Edge>,
}

/// How a solve went.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solved {
    pub iterations: usize,
    /// The weighted squared error before and after.
    pub error_before: f64,
    pub error_after: f64,
}

/// Gauss-Newton stops when no node moves more than this, metres or radians.
const CONVERGED: f64 = 1e-5;
/// ...or after this many iterations.
const MAX_ITERATIONS: usize = 20;
/// The information that pins the first node where it is (gauge freedom).
const ANCHOR: f64 = 1e9;

impl PoseGraph {
    /// The weighted squared error of every edge (the objective, Grisetti et al. eq. 4).
    pub fn error(&self) -> f64 {
        self.edges
            .iter()
            .map(|e| {
                let r = residual(self.poses[e.from], self.poses[e.to], e.relative);
                r.dot(&(e.information * r))
            })
            .sum()
    }

    /// Which nodes a path of edges joins to `from` within `budget` metres, a path's length
    /// the sum of the straight distances between the poses it passes (Dijkstra's shortest
    /// paths, stopped at the budget): the parts of the map already tied to it, where a
    /// loop closure would close nothing new.
    pub fn near_along_edges(&self, from: usize, budget: f64) -> Vec<bool> {
        use std::cmp::Reverse;
        use std::collections::BinaryHeap;
        let n = self.poses.len();
        let mut next: Vec<Vec<usize>> = vec![Vec::new(); n];
        for e in &self.edges {
            next[e.from].push(e.to);
            next[e.to].push(e.from);
        }
        let mut best = vec![f64::INFINITY; n];
        let mut near = vec![false; n];
        let mut queue = BinaryHeap::new();
        best[from] = 0.0;
        // Distances in micrometres as integers: the heap needs a total order.
        queue.push(Reverse((0u64, from)));
        while let Some(Reverse((_, k))) = queue.pop() {
            if near[k] {
                continue;
            }
            near[k] = true;
            for &j in &next[k] {
                let d = best[k] + self.poses[k].position().distance(self.poses[j].position());
                if d <= budget && d < best[j] {
                    best[j] = d;
                    queue.push(Reverse(((d * 1e6) as u64, j)));
                }
            }
        }
        near
    }

    /// Moves the nodes to the least-squares fit of every edge, the first node held
    /// fixed. Gauss-Newton on the sparse normal equations H dx = -b, factored by sparse
    /// Cholesky (Grisetti et al. algorithm 1). `None` when there is nothing to solve or
    /// the system is singular (a node joined by no edge).
    pub fn optimize(&mut self) -> Option<Solved> {
        let n = self.poses.len();
        if n < 2 || self.edges.is_empty() {
            return None;
        }
        let error_before = self.error();
        let mut iterations = 0;
        while iterations < MAX_ITERATIONS {
            iterations += 1;
            let step = self.gauss_newton_step()?;
            let mut largest: f64 = 0.0;
            for (k, pose) in self.poses.iter_mut().enumerate() {
                let d = Vector3::new(step[3 * k], step[3 * k + 1], step[3 * k + 2]);
                largest = largest.max(d.amax());
                pose.x += d[0];
                pose.y += d[1];
                pose.theta = wrap_angle(pose.theta + d[2]);
            }
            if largest < CONVERGED {
                break;
            }
        }
        Some(Solved {
            iterations,
            error_before,
            error_after: self.error(),
        })
    }

    /// One linearised solve: the step for every node.
    fn gauss_newton_step(&self) -> Option<DVector<f64>> {
        let n = self.poses.len();
        let mut h = CooMatrix::new(3 * n, 3 * n);
        let mut b = DVector::zeros(3 * n);
        for e in &self.edges {
            let (xi, xj) = (self.poses[e.from], self.poses[e.to]);
            let r = residual(xi, xj, e.relative);
            let (a, bj) = jacobians(xi, xj, e.relative);
            let omega = &e.information;
            let blocks = [(e.from, a), (e.to, bj)];
            for &(p, jp) in &blocks {
                let g = jp.transpose() * omega * r;
                for k in 0..3 {
                    b[3 * p + k] += g[k];
                }
                for &(q, jq) in &blocks {
                    push_block(&mut h, p, q, &(jp.transpose() * omega * jq));
                }
            }
        }
        push_block(&mut h, 0, 0, &(Matrix3::identity() * ANCHOR));
        let h = CscMatrix::from(&h);
        let chol = CscCholesky::factor(&h).ok()?;
        let dx = chol.solve(&(-b));
        let dx = dx.column(0).into_owned();
        dx.iter().all(|v| v.is_finite()).then_some(dx)
    }
}

/// Adds a 3x3 block at node rows `p`, columns `q` (duplicates sum when compressed).
fn push_block(h: &mut CooMatrix<f64>, p: usize, q: usize, m: &Matrix3<f64>) {
    for r in 0..3 {
        for c in 0..3 {
            if m[(r, c)] != 0.0 {
                h.push(3 * p + r, 3 * q + c, m[(r, c)]);
            }
        }
    }
}

/// The error of an edge: how the measured pose of j in i's frame differs from the poses'
/// (Grisetti et al. eq. 30: e = t2v(Z⁻¹ (Xi⁻¹ Xj)), here in its linear form).
pub fn residual(xi: Pose2, xj: Pose2, z: Pose2) -> Vector3<f64> {
    let (si, ci) = xi.theta.sin_cos();
    let (sz, cz) = z.theta.sin_cos();
    let (dx, dy) = (xj.x - xi.x, xj.y - xi.y);
    // Ri^T (tj - ti), then its difference from tij, rotated by Rij^T.
    let (lx, ly) = (ci * dx + si * dy, -si * dx + ci * dy);
    let (ex, ey) = (lx - z.x, ly - z.y);
    Vector3::new(
        cz * ex + sz * ey,
        -sz * ex + cz * ey,
        wrap_angle(xj.theta - xi.theta - z.theta),
    )
}

/// The residual's Jacobians with respect to xi and xj (Grisetti et al. eqs. 32-35).
fn jacobians(xi: Pose2, xj: Pose2, z: Pose2) -> (Matrix3<f64>, Matrix3<f64>) {
    let (si, ci) = xi.theta.sin_cos();
    let (sz, cz) = z.theta.sin_cos();
    let (dx, dy) = (xj.x - xi.x, xj.y - xi.y);
    // Rz^T Ri^T as one rotation by -(θi + θz).
    let (s, c) = (si * cz + ci * sz, ci * cz - si * sz);
    // d(Ri^T)/dθi (tj - ti), then rotated by Rz^T.
    let (ux, uy) = (-si * dx + ci * dy, -ci * dx - si * dy);
    let (vx, vy) = (cz * ux + sz * uy, -sz * ux + cz * uy);
    let a = Matrix3::new(-c, -s, vx, s, -c, vy, 0.0, 0.0, -1.0);
    let b = Matrix3::new(c, s, 0.0, -s, c, 0.0, 0.0, 0.0, 1.0);
    (a, b)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn edge(from: usize, to: usize, relative: Pose2, kind: EdgeKind) -> Edge {
        Edge {
            from,
            to,
            relative,
            information: Matrix3::from_diagonal(&Vector3::new(100.0, 100.0, 400.0)),
            kind,
        }
    }

    #[test]
    fn jacobians_match_finite_differences() {
        let (xi, xj, z) = (
            Pose2::new(0.3, -1.2, 0.8),
            Pose2::new(1.1, 0.4, -2.5),
            Pose2::new(0.5, 0.2, 0.3),
        );
        let (a, b) = jacobians(xi, xj, z);
        let h = 1e-6;
        for k in 0..3 {
            let bump = |p: Pose2, s: f64| {
                let mut q = p;
                match k {
                    0 => q.x += s,
                    1 => q.y += s,
                    _ => q.theta += s,
                }
                q
            };
            let da = (residual(bump(xi, h), xj, z) - residual(bump(xi, -h), xj, z)) / (2.0 * h);
            let db = (residual(xi, bump(xj, h), z) - residual(xi, bump(xj, -h), z)) / (2.0 * h);
            for r in 0..3 {
                assert!((a[(r, k)] - da[r]).abs() < 1e-6, "A[{r},{k}]");
                assert!((b[(r, k)] - db[r]).abs() < 1e-6, "B[{r},{k}]");
            }
        }
    }

    /// A square driven with odometry that turned 3° too little at each corner: the loop
    /// closure back to the start pulls the corners into place.
    #[test]
    fn a_loop_closure_straightens_a_drifted_square() {
        let side = Pose2::new(2.0, 0.0, std::f64::consts::FRAC_PI_2);
        let drifted = Pose2::new(2.0, 0.0, std::f64::consts::FRAC_PI_2 - 3f64.to_radians());
        let mut g = PoseGraph::default();
        g.poses.push(Pose2::default());
        for k in 0..4 {
            let last = g.poses[k];
            g.poses.push(last.compose(drifted));
            g.edges.push(edge(k, k + 1, side, EdgeKind::Sequential));
        }
        // Node 4 is back at the start, seen as such.
        let before = g.poses[4].position().distance(g.poses[0].position());
        assert!(before > 0.2, "the drift is visible: {before}");
        g.edges.push(edge(4, 0, Pose2::default(), EdgeKind::Loop));
        let solved = g.optimize().unwrap();
        assert!(solved.error_after < 1e-9 * solved.error_before.max(1.0));
        assert!(g.poses[4].position().distance(g.poses[0].position()) < 1e-6);
        assert!((g.poses[2].x - 2.0).abs() < 1e-6 && (g.poses[2].y - 2.0).abs() < 1e-6);
        // The first node stayed where it was.
        assert!(g.poses[0].position().distance(Default::default()) < 1e-6);
    }

    #[test]
    fn nodes_near_along_edges_follow_the_edges_not_the_distance() {
        // A chain 0-1-2-3 along x, 1 m apart, and 4 beside 0 but joined only to 3.
        let mut g = PoseGraph {
            poses: (0..4).map(|k| Pose2::new(k as f64, 0.0, 0.0)).collect(),
            edges: Vec::new(),
        };
        g.poses.push(Pose2::new(0.0, 0.5, 0.0));
        for k in 0..3 {
            g.edges.push(edge(
                k,
                k + 1,
                Pose2::new(1.0, 0.0, 0.0),
                EdgeKind::Sequential,
            ));
        }
        g.edges
            .push(edge(3, 4, Pose2::default(), EdgeKind::Sequential));
        let near = g.near_along_edges(0, 2.5);
        assert_eq!(near, vec![true, true, true, false, false]);
        // A loop edge from 4 to 0 ties them.
        g.edges.push(edge(0, 4, Pose2::default(), EdgeKind::Loop));
        assert!(g.near_along_edges(0, 2.5)[4]);
    }

    #[test]
    fn an_unconnected_node_is_no_solve() {
        let mut g = PoseGraph {
            poses: vec![
                Pose2::default(),
                Pose2::new(1.0, 0.0, 0.0),
                Pose2::default(),
            ],
            edges: Vec::new(),
        };
        g.edges
            .push(edge(0, 1, Pose2::new(1.0, 0.0, 0.0), EdgeKind::Sequential));
        assert_eq!(g.optimize(), None);
    }
}
