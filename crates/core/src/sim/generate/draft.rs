//! A world under construction: the boundary with its markers, interior walls with markers
//! on both faces, boxes with face markers, and the distance queries that placing needs.

use super::draw::tidy;
use super::rules::GATE_WIDTH;
use crate::geometry::{Point2, Pose2, Segment, wrap_angle};
use crate::perception::markers::MarkerCategory;
use crate::sim::shapes::{rect_contains, rect_corners, rect_edges, rect_faces, segment_distance2};
use crate::sim::{BlockColor, Gate, Marker, Obstacle, World};
use std::f64::consts::FRAC_PI_2;

/// First obstacle marker id (seed 001 section 1: obstacles 301-400).
const FIRST_OBSTACLE_ID: u32 = 301;

/// A place for a gate: midway between two neighbouring boundary markers.
#[derive(Clone, Copy, Debug)]
pub struct Slot {
    pub at: Point2,
    /// Into the world, radians.
    pub normal: f64,
    /// Index of its boundary segment in `world.walls`.
    pub wall: usize,
}

pub struct Draft {
    pub world: World,
    /// Indices in `world.walls` of walls (boundary and interior), not box outlines.
    pub walls: Vec<usize>,
    /// How many of `walls` (the first) are the boundary.
    pub boundary_walls: usize,
    pub slots: Vec<Slot>,
    /// Gaps left in interior walls.
    pub doors: Vec<Segment>,
    /// Gates' drop lanes: from just in front of the gate to beyond its last drop place.
    pub lanes: Vec<Segment>,
    /// Floor closed in by walls (a loop's island): nothing is placed there.
    pub islands: Vec<Obstacle>,
    /// Wall markers every this many metres.
    pub spacing: f64,
    /// Every doorway and corridor turn this wide, metres; `None`: drawn.
    pub doorway: Option<f64>,
    next_wall_id: u32,
    next_box_id: u32,
}

impl Draft {
    /// A `width` x `height` world with its boundary: a counter-clockwise wall with markers
    /// every `spacing` metres facing inward, numbered from 1 (as maps/arena.toml's).
    pub fn new(name: String, width: f64, height: f64, spacing: f64) -> Draft {
        let (hw, hh) = (width / 2.0, height / 2.0);
        let corners = [(-hw, -hh), (hw, -hh), (hw, hh), (-hw, hh)].map(|(x, y)| Point2::new(x, y));
        let mut draft = Draft {
            world: World {
                name,
                width,
                height,
                start: Pose2::default(),
                walls: Vec::new(),
                markers: Vec::new(),
                blocks: Vec::new(),
                gates: Vec::new(),
                obstacles: Vec::new(),
                track: None,
            },
            walls: Vec::new(),
            boundary_walls: 4,
            slots: Vec::new(),
            doors: Vec::new(),
            lanes: Vec::new(),
            islands: Vec::new(),
            spacing,
            doorway: None,
            next_wall_id: 1,
            next_box_id: FIRST_OBSTACLE_ID,
        };
        for k in 0..4 {
            let s = Segment::new(corners[k], corners[(k + 1) % 4]);
            let spots = draft.add_wall(s, &[FRAC_PI_2]);
            let heading = (s.b.y - s.a.y).atan2(s.b.x - s.a.x);
            for pair in spots.windows(2) {
                draft.slots.push(Slot {
                    at: mid(pair[0], pair[1]),
                    normal: wrap_angle(heading + FRAC_PI_2),
                    wall: draft.world.walls.len() - 1,
                });
            }
        }
        draft.next_wall_id += 1;
        draft
    }

    /// An interior wall from `a` to `b` with markers on both faces. Its ids follow the
    /// last wall's after a gap of one, so the planning map never joins two walls (it joins
    /// boundary markers with consecutive ids, map/landmark_layer.rs).
    pub fn add_interior(&mut self, a: Point2, b: Point2) -> Result<(), String> {
        self.add_wall(Segment::new(a, b), &[FRAC_PI_2, -FRAC_PI_2]);
        self.next_wall_id += 1;
        if MarkerCategory::of(self.next_wall_id - 2) != MarkerCategory::Boundary {
            return Err(
                "the interior walls carry more markers than the boundary ids 1-300 hold".into(),
            );
        }
        Ok(())
    }

    /// A closed island of walls round the axis-aligned rectangle from `lo` (lower-left) to
    /// `hi` (upper-right), markers on its outer faces only: the inside is closed to the robot.
    /// Each side's ids follow the last wall's after a gap of one, as `add_interior`'s.
    pub fn add_island(&mut self, lo: Point2, hi: Point2) -> Result<(), String> {
        // Clockwise, so each side's left face looks out of the island.
        let corners = [(lo.x, lo.y), (lo.x, hi.y), (hi.x, hi.y), (hi.x, lo.y)]
            .map(|(x, y)| Point2::new(x, y));
        for k in 0..4 {
            self.add_wall(Segment::new(corners[k], corners[(k + 1) % 4]), &[FRAC_PI_2]);
            self.next_wall_id += 1;
        }
        if MarkerCategory::of(self.next_wall_id - 2) != MarkerCategory::Boundary {
            return Err(
                "the island's walls carry more markers than the boundary ids 1-300 hold".into(),
            );
        }
        let centre = Point2::new((lo.x + hi.x) / 2.0, (lo.y + hi.y) / 2.0);
        self.islands.push(Obstacle {
            pose: Pose2::new(centre.x, centre.y, 0.0),
            width: hi.x - lo.x,
            height: hi.y - lo.y,
        });
        Ok(())
    }

    /// A wall segment with markers every `spacing` metres centred on it, at least one
    /// (build.rs's rule for `markers = { spacing }`), on the faces turned `sides` from its
    /// heading. Returns the marker spots.
    fn add_wall(&mut self, s: Segment, sides: &[f64]) -> Vec<Point2> {
        let len = s.length();
        let spacing = self.spacing;
        let n = (len / spacing + 1e-9).floor().max(1.0) as usize;
        let first = (len - (n - 1) as f64 * spacing) / 2.0;
        let (ux, uy) = ((s.b.x - s.a.x) / len, (s.b.y - s.a.y) / len);
        let heading = uy.atan2(ux);
        let mut spots = Vec::with_capacity(n);
        for k in 0..n {
            let d = first + k as f64 * spacing;
            let at = Point2::new(tidy(s.a.x + ux * d), tidy(s.a.y + uy * d));
            for side in sides {
                self.world.markers.push(Marker {
                    id: self.next_wall_id,
                    position: at,
                    normal: wrap_angle(heading + side),
                });
                self.next_wall_id += 1;
            }
            spots.push(at);
        }
        self.walls.push(self.world.walls.len());
        self.world.walls.push(s);
        spots
    }

    /// A box with markers on its faces (+x, +y, -x, -y), but none on face `bare`.
    pub fn add_box(&mut self, pose: Pose2, w: f64, h: f64, bare: Option<usize>) {
        for (k, (at, facing)) in rect_faces(pose, w, h).into_iter().enumerate() {
            if Some(k) != bare {
                self.world.markers.push(Marker {
                    id: self.next_box_id + k as u32,
                    position: at,
                    normal: wrap_angle(facing),
                });
            }
        }
        self.next_box_id += 4;
        self.world.walls.extend(rect_edges(pose, w, h));
        self.world.obstacles.push(Obstacle {
            pose,
            width: w,
            height: h,
        });
    }

    /// A gate of `color` with markers `ids` `GATE_WIDTH` apart across `slot`, `ids[0]` on
    /// the left seen from inside (build.rs's placement for `[[gates]]`).
    pub fn add_gate(&mut self, color: BlockColor, ids: [u32; 2], slot: Slot) {
        let (s, c) = (slot.normal + FRAC_PI_2).sin_cos();
        for (id, offset) in ids.into_iter().zip([-GATE_WIDTH / 2.0, GATE_WIDTH / 2.0]) {
            self.world.markers.push(Marker {
                id,
                position: Point2::new(slot.at.x + c * offset, slot.at.y + s * offset),
                normal: slot.normal,
            });
        }
        self.world.gates.push(Gate {
            color,
            markers: ids,
        });
    }

    /// Distance from `p` to the nearest wall or box, zero inside a box or an island.
    pub fn clearance(&self, p: Point2) -> f64 {
        if self.inside_box(p) {
            return 0.0;
        }
        self.world
            .walls
            .iter()
            .map(|w| w.distance_squared_to(p))
            .fold(f64::INFINITY, f64::min)
            .sqrt()
    }

    /// Distance from the segment `s` to the nearest wall or box outline but `skip`.
    pub fn segment_clearance(&self, s: Segment, skip: Option<usize>) -> f64 {
        self.world
            .walls
            .iter()
            .enumerate()
            .filter(|(k, _)| Some(*k) != skip)
            .map(|(_, w)| segment_distance2(s.a, s.b, *w))
            .fold(f64::INFINITY, f64::min)
            .sqrt()
    }

    /// Distance from a box to the nearest wall or box but wall `skip`; zero when it
    /// overlaps one or leaves the world.
    pub fn box_clearance(&self, pose: Pose2, w: f64, h: f64, skip: Option<usize>) -> f64 {
        let corners = rect_corners(pose, w, h);
        let outside = corners.iter().any(|c| !self.world.contains(*c));
        let nested = self.inside_box(pose.position())
            || self
                .world
                .walls
                .iter()
                .any(|s| rect_contains(pose, w, h, s.a));
        if outside || nested {
            return 0.0;
        }
        rect_edges(pose, w, h)
            .into_iter()
            .map(|e| self.segment_clearance(e, skip))
            .fold(f64::INFINITY, f64::min)
    }

    /// Whether `p` lies inside a box or an island.
    fn inside_box(&self, p: Point2) -> bool {
        (self.world.obstacles.iter())
            .chain(&self.islands)
            .any(|o| rect_contains(o.pose, o.width, o.height, p))
    }

    /// Distance from `p` to the nearest gate lane.
    pub fn lane_distance(&self, p: Point2) -> f64 {
        self.lanes
            .iter()
            .map(|l| l.distance_to(p))
            .fold(f64::INFINITY, f64::min)
    }

    /// Distance from `p` to the nearest fixed marker.
    pub fn marker_distance(&self, p: Point2) -> f64 {
        self.world
            .markers
            .iter()
            .map(|m| m.position.distance(p))
            .fold(f64::INFINITY, f64::min)
    }

    /// Distance from `p` to the nearest doorway.
    pub fn door_distance(&self, p: Point2) -> f64 {
        self.doors
            .iter()
            .map(|d| d.distance_to(p))
            .fold(f64::INFINITY, f64::min)
    }
}

fn mid(a: Point2, b: Point2) -> Point2 {
    Point2::new(tidy((a.x + b.x) / 2.0), tidy((a.y + b.y) / 2.0))
}
