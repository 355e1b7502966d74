//! Closing loops: a new keyframe matched against an older part of the map that the graph
//! does not already tie to it, gated by the match's quality, its spread and the path's
//! uncertainty, then the graph solved; and a continued map's first keyframe joined to the
//! saved graph the same way.

use super::graph::{Edge, EdgeKind};
use super::keyframes::Keyframe;
use super::matcher::{self, Match, Window};
use super::{
    Closure, JOIN_STD, LOOP_CHAIN_SHARE, LOOP_GATE_CHI2, LOOP_GATE_FLOOR, LOOP_TRY_EVERY,
    LidarSlam, MIN_POINTS, Update, information, rotate,
};
use crate::data::LaserScan;
use crate::geometry::{Point2, Pose2, wrap_angle};
use nalgebra::{Matrix3, Vector3};

impl LidarSlam {
    /// Tries to close a loop from keyframe `new` to an older part of the map.
    pub(super) fn close_loop(&mut self, new: usize) -> Option<Closure> {
        let c = self.config.clone();
        let here = self.graph.poses[new];
        let travelled = self.frames[new].travelled;
        if travelled - self.last_loop_try < LOOP_TRY_EVERY {
            return None;
        }
        // Nodes the graph already ties to this one within the loop's minimum length are
        // no loop: only a part of the map reached the long way round is.
        let tied = self.graph.near_along_edges(new, c.loop_minimum_travel);
        let old = (0..new)
            .filter(|&k| !tied[k])
            .map(|k| (k, self.graph.poses[k].position().distance(here.position())))
            .filter(|&(_, d)| d <= c.loop_search_maximum_distance)
            .min_by(|a, b| a.1.total_cmp(&b.1))?
            .0;
        self.last_loop_try = travelled;
        let half = (c.scan_buffer_size as usize / LOOP_CHAIN_SHARE).max(1);
        let lo = old.saturating_sub(half);
        let hi = (old + half + 1).min(new);
        let chain: Vec<usize> = (lo..hi).filter(|&k| !tied[k]).collect();
        let (first, last) = (*chain.first()?, *chain.last()? + 1);
        let window = Window {
            half_width: c.loop_search_half_width,
            half_angle: c.loop_search_half_angle_deg.to_radians(),
        };
        let (fine, coarse) = self.field_of(first..last, c.loop_search_half_width)?;
        let points = &self.frames[new].points;
        if points.len() < MIN_POINTS {
            return None;
        }
        let m = matcher::correlate(&fine, &coarse, points, here, window)?;
        if m.response < c.loop_minimum_response || m.position_std() > c.loop_maximum_std {
            return None;
        }
        if !self.plausible(old, new, &m) {
            return None;
        }
        let relative = self.graph.poses[old].between(m.pose);
        let cov_rel = rotate(&m.covariance, -self.graph.poses[old].theta);
        self.graph.edges.push(Edge {
            from: old,
            to: new,
            relative,
            information: information(&cov_rel),
            kind: EdgeKind::Loop,
        });
        let before = self.graph.poses.clone();
        self.graph.optimize()?;
        let moved = self.graph.poses[new].position().distance(here.position());
        let largest_shift = (before.iter().zip(&self.graph.poses))
            .map(|(a, b)| a.position().distance(b.position()))
            .fold(0.0, f64::max);
        self.loops += 1;
        // The new node is now known as well as the old one and the match.
        let joined = self.frames[old].covariance + m.covariance;
        if joined.trace() < self.frames[new].covariance.trace() {
            self.frames[new].covariance = joined;
        }
        self.covariance = self.frames[new].covariance;
        let f = &self.frames[new];
        self.correction = self.graph.poses[new].compose(f.odom.inverse());
        self.rebuild_local();
        Some(Closure {
            old,
            new,
            correction: moved,
            largest_shift,
            response: m.response,
        })
    }

    /// Whether a loop match's correction is within what the path's uncertainty allows.
    fn plausible(&self, old: usize, new: usize, m: &Match) -> bool {
        let here = self.graph.poses[new];
        let d = Vector3::new(
            m.pose.x - here.x,
            m.pose.y - here.y,
            wrap_angle(m.pose.theta - here.theta),
        );
        let grown = self.frames[new].covariance - self.frames[old].covariance;
        let (fp, fa) = (LOOP_GATE_FLOOR.0, LOOP_GATE_FLOOR.1.to_radians());
        let floor = Matrix3::from_diagonal(&Vector3::new(fp * fp, fp * fp, fa * fa));
        let s = positive_part(&grown) + m.covariance + floor;
        s.cholesky()
            .is_some_and(|ch| d.dot(&ch.solve(&d)) <= LOOP_GATE_CHI2)
    }

    /// A continued map's first keyframe, joined to the saved graph's nearest node.
    pub(super) fn join(
        &mut self,
        start: Pose2,
        odom: Pose2,
        scan: &LaserScan,
        points: &[Point2],
    ) -> Update {
        let c = self.config.clone();
        let near = (0..self.loaded)
            .min_by(|&a, &b| {
                let d = |k: usize| self.graph.poses[k].position().distance(start.position());
                d(a).total_cmp(&d(b))
            })
            .unwrap_or(0);
        let lo = near.saturating_sub(c.scan_buffer_size as usize);
        let hi = (near + c.scan_buffer_size as usize + 1).min(self.loaded);
        let window = Window {
            half_width: c.loop_search_half_width,
            half_angle: c.loop_search_half_angle_deg.to_radians(),
        };
        let matched = (points.len() >= MIN_POINTS)
            .then(|| self.field_of(lo..hi, c.loop_search_half_width))
            .flatten()
            .and_then(|(fine, coarse)| matcher::correlate(&fine, &coarse, points, start, window))
            .filter(|m| {
                m.response >= c.loop_minimum_response && m.position_std() <= c.loop_maximum_std
            });
        let (pose, cov) = match matched {
            Some(m) => (m.pose, m.covariance),
            None => {
                let (sp, sa) = (JOIN_STD.0, JOIN_STD.1.to_radians());
                (
                    start,
                    Matrix3::from_diagonal(&Vector3::new(sp * sp, sp * sp, sa * sa)),
                )
            }
        };
        self.correction = pose.compose(odom.inverse());
        let rel = self.graph.poses[near].between(pose);
        let cov_rel = rotate(&cov, -self.graph.poses[near].theta);
        let travelled = self.last_loop_try;
        let node = self.graph.poses.len();
        let mut frame = Keyframe::new(pose, scan.clone(), c.resolution, travelled);
        frame.odom = odom;
        frame.covariance = cov;
        self.graph.edges.push(Edge {
            from: near,
            to: node,
            relative: rel,
            information: information(&cov_rel),
            kind: if matched.is_some() {
                EdgeKind::Loop
            } else {
                EdgeKind::Sequential
            },
        });
        self.graph.poses.push(pose);
        self.frames.push(frame);
        self.covariance = cov;
        self.rebuild_local();
        Update {
            matched: matched.is_some(),
            keyframe: Some(node),
            closure: None,
            joined: Some(matched.is_some()),
        }
    }
}

/// The symmetric matrix with its negative eigenvalues set to zero.
fn positive_part(m: &Matrix3<f64>) -> Matrix3<f64> {
    let sym = (m + m.transpose()) / 2.0;
    let eig = sym.symmetric_eigen();
    let values = eig.eigenvalues.map(|v| v.max(0.0));
    eig.eigenvectors * Matrix3::from_diagonal(&values) * eig.eigenvectors.transpose()
}
