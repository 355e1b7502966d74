//! A `World` written back as a world file (the format of `maps/arena.toml`), so that
//! `World::from_toml(&world.to_toml(), ..)` gives the same world again.
//!
//! Walls come out as polylines (segments that join end to start), each box obstacle once
//! with its face markers, gates by their centre, facing and width, and every other marker
//! as a `[[markers]]` entry of its own.

use super::World;
use super::shapes::{rect_edges, rect_faces};
use super::world_file::{BlockSpec, GateSpec, MarkerSpec, ObstacleSpec, WallSpec, WorldFile};
use crate::geometry::{Point2, Segment, wrap_angle};
use crate::perception::markers::MarkerCategory;
use std::collections::HashSet;
use toml::Spanned;

/// Points this close are the same point, metres (far below any world's detail).
const SAME: f64 = 1e-9;

/// The world as world-file text.
pub fn to_toml(world: &World) -> String {
    let file = to_file(world);
    toml::to_string(&file).expect("a world file holds only numbers, strings and arrays")
}

fn to_file(world: &World) -> WorldFile {
    let mut used = HashSet::new();
    let obstacles: Vec<Spanned<ObstacleSpec>> = world
        .obstacles
        .iter()
        .map(|o| {
            let faces = rect_faces(o.pose, o.width, o.height);
            let mut ids: Vec<u32> = faces
                .iter()
                .map(|&(at, facing)| {
                    world
                        .markers
                        .iter()
                        .find(|m| {
                            !used.contains(&m.id)
                                && MarkerCategory::of(m.id) == MarkerCategory::Obstacle
                                && m.position.distance(at) < SAME
                                && wrap_angle(m.normal - facing).abs() < 1e-6
                        })
                        .map_or(0, |m| {
                            used.insert(m.id);
                            m.id
                        })
                })
                .collect();
            while ids.last() == Some(&0) {
                ids.pop();
            }
            spanned(ObstacleSpec {
                center: [round(o.pose.x), round(o.pose.y)],
                size: [round(o.width), round(o.height)],
                yaw_deg: degrees(o.pose.theta),
                markers: ids,
            })
        })
        .collect();
    for gate in &world.gates {
        used.extend(gate.markers);
    }
    let markers = world
        .markers
        .iter()
        .filter(|m| !used.contains(&m.id))
        .map(|m| {
            spanned(MarkerSpec {
                id: m.id,
                x: round(m.position.x),
                y: round(m.position.y),
                facing_deg: degrees(m.normal),
            })
        })
        .collect();
    let gates = world
        .gates
        .iter()
        .filter_map(|g| {
            let (a, b) = (world.marker(g.markers[0])?, world.marker(g.markers[1])?);
            let pose = world.gate_pose(g)?;
            Some(spanned(GateSpec {
                color: g.color,
                markers: g.markers,
                center: [round(pose.x), round(pose.y)],
                facing_deg: degrees(pose.theta),
                width: round(a.position.distance(b.position)),
            }))
        })
        .collect();
    let blocks = world
        .blocks
        .iter()
        .map(|b| {
            spanned(BlockSpec {
                color: b.color,
                x: round(b.pose.x),
                y: round(b.pose.y),
                yaw_deg: degrees(b.pose.theta),
                markers: b.markers,
                size: round(b.size),
            })
        })
        .collect();
    let s = world.start;
    WorldFile {
        name: spanned(world.name.clone()),
        size: spanned([round(world.width), round(world.height)]),
        start: spanned([round(s.x), round(s.y), degrees(s.theta)]),
        walls: polylines(&plain_walls(world))
            .into_iter()
            .map(spanned)
            .collect(),
        obstacles,
        markers,
        gates,
        blocks,
        track: world.track.as_ref().map(|t| spanned(t.spec.clone())),
    }
}

/// The wall segments that are not an obstacle's or a track post's outline.
fn plain_walls(world: &World) -> Vec<Segment> {
    let mut walls = world.walls.clone();
    let posts = world.track.iter().flat_map(|t| t.post_outlines());
    let outlines = (world.obstacles.iter()).flat_map(|o| rect_edges(o.pose, o.width, o.height));
    for edge in outlines.chain(posts) {
        {
            if let Some(k) = walls
                .iter()
                .position(|w| w.a.distance(edge.a) < SAME && w.b.distance(edge.b) < SAME)
            {
                walls.remove(k);
            }
        }
    }
    walls
}

/// Segments joined into polylines where one ends at the next one's start; a polyline of
/// three or more segments that comes back to its first point is closed.
fn polylines(segments: &[Segment]) -> Vec<WallSpec> {
    let mut out: Vec<Vec<Point2>> = Vec::new();
    for s in segments {
        match out.last_mut() {
            Some(line) if line.last().is_some_and(|p| p.distance(s.a) < SAME) => line.push(s.b),
            _ => out.push(vec![s.a, s.b]),
        }
    }
    out.into_iter()
        .map(|mut points| {
            let closed = points.len() >= 4 && points[0].distance(points[points.len() - 1]) < SAME;
            if closed {
                points.pop();
            }
            WallSpec {
                points: points.iter().map(|p| [round(p.x), round(p.y)]).collect(),
                closed,
                markers: None,
            }
        })
        .collect()
}

fn spanned<T>(value: T) -> Spanned<T> {
    Spanned::new(0..0, value)
}

/// `v` rounded to 9 decimals (nanometres, far below any world's detail), so that
/// 90.00000000000001 degrees reads 90; never a negative zero.
fn round(v: f64) -> f64 {
    let r: f64 = format!("{v:.9}").parse().unwrap_or(v);
    if r == 0.0 { 0.0 } else { r }
}

fn degrees(radians: f64) -> f64 {
    round(wrap_angle(radians).to_degrees())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    /// Markers sorted by id, so worlds can be compared whatever order a file listed them in.
    fn sorted(mut w: World) -> World {
        w.markers.sort_by_key(|m| m.id);
        w
    }

    fn close(a: &World, b: &World) {
        assert_eq!(a.name, b.name);
        assert_eq!(a.walls.len(), b.walls.len());
        for (p, q) in a.walls.iter().zip(&b.walls) {
            assert!(
                p.a.distance(q.a) < 1e-9 && p.b.distance(q.b) < 1e-9,
                "{p:?} {q:?}"
            );
        }
        assert_eq!(a.markers.len(), b.markers.len());
        for (p, q) in a.markers.iter().zip(&b.markers) {
            assert_eq!(p.id, q.id);
            assert!(p.position.distance(q.position) < 1e-9, "{p:?} {q:?}");
            assert!(wrap_angle(p.normal - q.normal).abs() < 1e-9, "{p:?} {q:?}");
        }
        assert_eq!(a.gates, b.gates);
        assert_eq!(a.track, b.track);
        assert_eq!(a.obstacles.len(), b.obstacles.len());
        assert_eq!(a.blocks.len(), b.blocks.len());
        for (p, q) in a.blocks.iter().zip(&b.blocks) {
            assert_eq!((p.color, p.markers), (q.color, q.markers));
            assert!(p.pose.position().distance(q.pose.position()) < 1e-9);
        }
    }

    #[test]
    fn every_shipped_world_reads_back_the_same() {
        let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
        for file in [
            "maps/arena.toml",
            "maps/warehouse.toml",
            "maps/track.toml",
            "tests/worlds/hidden_box.toml",
            "tests/worlds/walled_garden.toml",
        ] {
            let world = World::load(&root.join(file)).unwrap();
            let text = to_toml(&world);
            let back = World::from_toml(&text, Path::new(file))
                .unwrap_or_else(|e| panic!("{file}: {e}\n{text}"));
            close(&sorted(world), &sorted(back.clone()));
            // Written again, the text does not change.
            assert_eq!(to_toml(&back), text, "{file}");
        }
    }

    #[test]
    fn numbers_are_written_round() {
        assert_eq!(round(0.1 + 0.2), 0.3);
        assert_eq!(round(-1e-12).to_string(), "0");
        assert_eq!(degrees(std::f64::consts::FRAC_PI_2), 90.0);
        let text = to_toml(&World::default_arena());
        assert!(text.contains("closed = true"), "{text}");
        assert!(text.contains("facing_deg = 180.0"), "{text}");
    }
}
