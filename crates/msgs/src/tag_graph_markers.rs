//! Route mode's tag graph (seed 003) as RViz markers: each tag a flat square with its id
//! above it, the edges in grey, the route being driven as a thicker green line, edges
//! found blocked in red, and the tag the robot is heading for ringed in amber. Every
//! marker has a fixed namespace and id, and a DELETEALL goes first, so RViz replaces the
//! last graph rather than piling graphs up, and what the robot no longer drives vanishes.

use crate::ros::{self as msgs, ColorRgba, Header, MarkerHumble, Time, Vector3};
use navdeck_core::geometry::Point2;
use navdeck_core::tags::TagId;

/// The namespace of the graph's shapes (tags, edges, route, blocked edges, next tag).
pub const NS: &str = "tag_graph";
/// The namespace of the tags' labels, each with its tag's id as the marker's id.
pub const NS_IDS: &str = "tag_graph/ids";
/// The shapes' ids in `NS`.
pub const ID_TAGS: i32 = 0;
pub const ID_EDGES: i32 = 1;
pub const ID_ROUTE: i32 = 2;
pub const ID_BLOCKED: i32 = 3;
pub const ID_NEXT: i32 = 4;

/// A tag's printed square with its white border, metres (perception/tag_camera.rs:
/// navdeck's tags are a 50 mm black square, 62.5 mm printed).
pub const TAG_SIDE: f64 = 0.0625;
/// How thick the tags' squares are drawn, metres (navdeck's, as the sizes below).
const TAG_THICKNESS: f64 = 0.005;
/// Line widths, metres: the edges, the route, the blocked edges.
const EDGE_WIDTH: f64 = 0.01;
const ROUTE_WIDTH: f64 = 0.03;
const BLOCKED_WIDTH: f64 = 0.03;
/// The ring round the next tag, as a multiple of the tag's side.
const NEXT_SIDE: f64 = 1.6;
/// How high the labels float above the floor and how tall their letters are, metres.
const LABEL_HEIGHT: f64 = 0.06;
const LABEL_SIZE: f64 = 0.05;

/// Route mode's tag graph as the runtime hands it to a link: the map's tags and edges,
/// the route being driven and the leg it is on, and the edges found blocked.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TagGraphPicture {
    /// Every tag of the map with where it lies in the map frame, by id.
    pub tags: Vec<(TagId, Point2)>,
    /// The map's edges as (from, to), each way the map lets it be driven.
    pub edges: Vec<(TagId, TagId)>,
    /// The tags of the route being driven, in order; empty when none is.
    pub route: Vec<TagId>,
    /// The leg being driven: from `route[leg]` to `route[leg + 1]`.
    pub leg: Option<usize>,
    /// Edges found blocked, as (from, to) the way they were driven.
    pub blocked: Vec<(TagId, TagId)>,
}

impl TagGraphPicture {
    /// The tag the robot is heading for: the end of the leg being driven.
    pub fn next(&self) -> Option<TagId> {
        self.route.get(self.leg? + 1).copied()
    }

    fn at(&self, id: TagId) -> Option<Point2> {
        (self.tags.iter()).find(|(t, _)| *t == id).map(|&(_, p)| p)
    }

    /// The points of (from, to) pairs whose tags are both known, at height `z`.
    fn pairs(&self, pairs: &[(TagId, TagId)], z: f64) -> Vec<Vector3> {
        (pairs.iter())
            .filter_map(|&(a, b)| Some([self.at(a)?, self.at(b)?]))
            .flatten()
            .map(|p| at_height(p, z))
            .collect()
    }
}

fn at_height(p: Point2, z: f64) -> Vector3 {
    Vector3 { x: p.x, y: p.y, z }
}

const GREY: [f32; 3] = [0.6, 0.6, 0.6];
const LIGHT: [f32; 3] = [0.9, 0.9, 0.9];
const GREEN: [f32; 3] = [0.1, 0.8, 0.2];
const RED: [f32; 3] = [1.0, 0.1, 0.1];
const AMBER: [f32; 3] = [1.0, 0.7, 0.0];

fn colour([r, g, b]: [f32; 3]) -> ColorRgba {
    ColorRgba { r, g, b, a: 1.0 }
}

/// The graph as a MarkerArray's markers in `frame`: DELETEALL, the tags (a CUBE_LIST,
/// those on the route green), the edges (LINE_LIST), the route (LINE_STRIP), the blocked
/// edges (LINE_LIST), the next tag (CUBE) and one TEXT_VIEW_FACING label a tag. A line
/// with nothing to draw is left out (RViz warns of empty line markers).
pub fn tag_graph_markers(g: &TagGraphPicture, stamp: Time, frame: &str) -> Vec<MarkerHumble> {
    let header = Header::new(stamp, frame);
    let shape =
        |id: i32, kind: i32, width: f64, rgb: [f32; 3], points: Vec<Vector3>| MarkerHumble {
            header: header.clone(),
            ns: NS.into(),
            id,
            kind,
            action: msgs::MARKER_ADD,
            pose: msgs::Pose::default(),
            scale: Vector3 {
                x: width,
                ..Default::default()
            },
            color: colour(rgb),
            points,
            ..Default::default()
        };
    let mut out = vec![MarkerHumble {
        header: header.clone(),
        action: msgs::MARKER_DELETEALL,
        ..Default::default()
    }];
    if !g.tags.is_empty() {
        let on_route = |id: &TagId| g.route.contains(id);
        out.push(MarkerHumble {
            scale: Vector3 {
                x: TAG_SIDE,
                y: TAG_SIDE,
                z: TAG_THICKNESS,
            },
            colors: (g.tags.iter())
                .map(|(id, _)| colour(if on_route(id) { GREEN } else { LIGHT }))
                .collect(),
            ..shape(
                ID_TAGS,
                msgs::MARKER_CUBE_LIST,
                TAG_SIDE,
                LIGHT,
                (g.tags.iter())
                    .map(|&(_, p)| at_height(p, TAG_THICKNESS / 2.0))
                    .collect(),
            )
        });
    }
    // Lines at heights that keep the route and blocked edges above the plain edges.
    let lines = [
        (ID_EDGES, EDGE_WIDTH, GREY, g.pairs(&g.edges, 0.001)),
        (ID_ROUTE, ROUTE_WIDTH, GREEN, route_points(g, 0.003)),
        (ID_BLOCKED, BLOCKED_WIDTH, RED, g.pairs(&g.blocked, 0.004)),
    ];
    for (id, width, rgb, points) in lines {
        if points.len() >= 2 {
            let kind = match id {
                ID_ROUTE => msgs::MARKER_LINE_STRIP,
                _ => msgs::MARKER_LINE_LIST,
            };
            out.push(shape(id, kind, width, rgb, points));
        }
    }
    if let Some(p) = g.next().and_then(|id| g.at(id)) {
        let side = NEXT_SIDE * TAG_SIDE;
        out.push(MarkerHumble {
            pose: msgs::Pose {
                position: at_height(p, TAG_THICKNESS / 4.0),
                ..Default::default()
            },
            scale: Vector3 {
                x: side,
                y: side,
                z: TAG_THICKNESS / 2.0,
            },
            ..shape(ID_NEXT, msgs::MARKER_CUBE, side, AMBER, Vec::new())
        });
    }
    for &(id, p) in &g.tags {
        out.push(MarkerHumble {
            header: header.clone(),
            ns: NS_IDS.into(),
            // The tag's id, its u32 bits read as i32: one marker id per tag id.
            id: id as i32,
            kind: msgs::MARKER_TEXT_VIEW_FACING,
            action: msgs::MARKER_ADD,
            pose: msgs::Pose {
                position: at_height(p, LABEL_HEIGHT),
                ..Default::default()
            },
            scale: Vector3 {
                z: LABEL_SIZE,
                ..Default::default()
            },
            color: colour(LIGHT),
            text: id.to_string(),
            ..Default::default()
        });
    }
    out
}

/// The route's tags in order, those the graph knows, at height `z`.
fn route_points(g: &TagGraphPicture, z: f64) -> Vec<Vector3> {
    (g.route.iter())
        .filter_map(|&id| g.at(id))
        .map(|p| at_height(p, z))
        .collect()
}

#[cfg(test)]
#[path = "tag_graph_markers_tests.rs"]
mod tests;
