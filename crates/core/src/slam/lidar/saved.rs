//! The pose graph as a file, so that mapping can go on where it stopped (slam_toolbox's
//! serialised pose graph and "continue mapping"): every keyframe's pose and scan, and
//! every edge. JSON, written beside the Nav2 map it was saved with.

use super::graph::{Edge, EdgeKind, PoseGraph};
use crate::data::LaserScan;
use crate::data::frame_check::{MAX_BEAMS, MAX_COORDINATE};
use crate::geometry::Pose2;
use nalgebra::Matrix3;
use serde::{Deserialize, Serialize};

/// What the file says it is.
pub const FORMAT: &str = "navdeck pose graph";
pub const VERSION: u32 = 1;
/// Most keyframes a file may hold: 100 000 scans of 360 beams is about 150 MB of JSON.
pub const MAX_NODES: usize = 100_000;
/// The file's name beside a Nav2 map `NAME.yaml`: `NAME.posegraph.json`.
pub const SUFFIX: &str = "posegraph.json";

/// The saved graph.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SavedGraph {
    pub format: String,
    pub version: u32,
    pub nodes: Vec<SavedNode>,
    pub edges: Vec<SavedEdge>,
}

/// One keyframe: its pose in the map frame (x, y metres, θ radians) and its scan.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SavedNode {
    pub pose: [f64; 3],
    pub angle_min: f64,
    pub angle_increment: f64,
    pub range_min: f64,
    pub range_max: f64,
    /// Ranges in metres; `null` where the beam saw nothing within range (REP-117's +inf),
    /// a negative number where something was closer than `range_min` (its -inf).
    pub ranges: Vec<Option<f32>>,
}

/// One edge: node `to`'s pose in node `from`'s frame, and the information matrix's upper
/// triangle (xx, xy, xθ, yy, yθ, θθ).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SavedEdge {
    pub from: usize,
    pub to: usize,
    pub kind: EdgeKind,
    pub relative: [f64; 3],
    pub information: [f64; 6],
}

impl SavedGraph {
    /// The graph of `poses`, `scans` (one per pose) and `edges`.
    pub fn new<'a>(
        poses: &[Pose2],
        scans: impl Iterator<Item = &'a LaserScan>,
        edges: &[Edge],
    ) -> SavedGraph {
        let nodes = poses
            .iter()
            .zip(scans)
            .map(|(p, s)| SavedNode {
                pose: [p.x, p.y, p.theta],
                angle_min: s.angle_min,
                angle_increment: s.angle_increment,
                range_min: s.range_min,
                range_max: s.range_max,
                ranges: s
                    .ranges
                    .iter()
                    .map(|&r| match r {
                        r if r.is_finite() => Some(r),
                        r if r < 0.0 => Some(-1.0),
                        _ => None,
                    })
                    .collect(),
            })
            .collect();
        let edges = edges
            .iter()
            .map(|e| {
                let i = &e.information;
                SavedEdge {
                    from: e.from,
                    to: e.to,
                    kind: e.kind,
                    relative: [e.relative.x, e.relative.y, e.relative.theta],
                    information: [
                        i[(0, 0)],
                        i[(0, 1)],
                        i[(0, 2)],
                        i[(1, 1)],
                        i[(1, 2)],
                        i[(2, 2)],
                    ],
                }
            })
            .collect();
        SavedGraph {
            format: FORMAT.into(),
            version: VERSION,
            nodes,
            edges,
        }
    }

    pub fn to_json(&self) -> String {
        serde_json::to_string(self).unwrap_or_default()
    }

    /// Reads and checks a file's text; the error names the field and value.
    pub fn from_json(text: &str) -> Result<SavedGraph, String> {
        let g: SavedGraph = serde_json::from_str(text).map_err(|e| e.to_string())?;
        g.check()?;
        Ok(g)
    }

    /// Every number finite and bounded, every edge between nodes that exist, at least one
    /// node: a file that passes can be continued without surprises.
    pub fn check(&self) -> Result<(), String> {
        if self.format != FORMAT {
            return Err(format!("format {:?} is not {FORMAT:?}", self.format));
        }
        if self.version != VERSION {
            return Err(format!("version {} is not {VERSION}", self.version));
        }
        if self.nodes.is_empty() || self.nodes.len() > MAX_NODES {
            return Err(format!(
                "nodes: {} keyframes, expected 1..={MAX_NODES}",
                self.nodes.len()
            ));
        }
        for (k, n) in self.nodes.iter().enumerate() {
            let bad = |what: &str, v: f64| Err(format!("nodes[{k}].{what}: {v} is out of range"));
            for (what, v) in [("pose x", n.pose[0]), ("pose y", n.pose[1])] {
                if v.is_nan() || v.abs() > MAX_COORDINATE {
                    return bad(what, v);
                }
            }
            if !n.pose[2].is_finite() {
                return bad("pose theta", n.pose[2]);
            }
            if !(n.angle_min.is_finite() && n.angle_increment.is_finite()) {
                return bad("angle_min or angle_increment", n.angle_min);
            }
            if !(n.range_min.is_finite() && n.range_min >= 0.0) {
                return bad("range_min", n.range_min);
            }
            if !(n.range_max.is_finite() && n.range_max > n.range_min && n.range_max <= 1000.0) {
                return bad("range_max", n.range_max);
            }
            if n.ranges.is_empty() || n.ranges.len() > MAX_BEAMS {
                return Err(format!(
                    "nodes[{k}].ranges: {} beams, expected 1..={MAX_BEAMS}",
                    n.ranges.len()
                ));
            }
            if let Some(r) = n.ranges.iter().flatten().find(|r| !r.is_finite()) {
                return bad("ranges", f64::from(*r));
            }
        }
        let count = self.nodes.len();
        for (k, e) in self.edges.iter().enumerate() {
            if e.from >= count || e.to >= count || e.from == e.to {
                return Err(format!(
                    "edges[{k}]: from {} to {} is not between two of the {count} nodes",
                    e.from, e.to
                ));
            }
            if let Some(v) = (e.relative.iter().chain(&e.information)).find(|v| !v.is_finite()) {
                return Err(format!("edges[{k}]: {v} is not a number"));
            }
            if information(e).cholesky().is_none() {
                return Err(format!("edges[{k}].information is not positive definite"));
            }
        }
        Ok(())
    }

    /// The graph and the keyframes' scans.
    pub fn into_parts(self) -> (PoseGraph, Vec<LaserScan>) {
        let poses = (self.nodes.iter())
            .map(|n| Pose2::new(n.pose[0], n.pose[1], crate::geometry::wrap_angle(n.pose[2])))
            .collect();
        let edges = (self.edges.iter())
            .map(|e| Edge {
                from: e.from,
                to: e.to,
                relative: Pose2::new(e.relative[0], e.relative[1], e.relative[2]),
                information: information(e),
                kind: e.kind,
            })
            .collect();
        let scans = (self.nodes.into_iter())
            .map(|n| LaserScan {
                angle_min: n.angle_min,
                angle_increment: n.angle_increment,
                range_min: n.range_min,
                range_max: n.range_max,
                ranges: (n.ranges.into_iter())
                    .map(|r| match r {
                        None => f32::INFINITY,
                        Some(r) if r < 0.0 => f32::NEG_INFINITY,
                        Some(r) => r,
                    })
                    .collect(),
            })
            .collect();
        (PoseGraph { poses, edges }, scans)
    }
}

/// The symmetric information matrix of a saved edge.
fn information(e: &SavedEdge) -> Matrix3<f64> {
    let i = &e.information;
    Matrix3::new(i[0], i[1], i[2], i[1], i[3], i[4], i[2], i[4], i[5])
}
