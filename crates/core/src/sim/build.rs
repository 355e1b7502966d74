//! Turns a parsed world file into a `World`, refusing content that breaks the rules.

use super::checks::{Checker, MAX_WORLD_SIDE, fmt_list, fmt_numbers, fmt_point};
use super::shapes::{rect_contains, rect_corners, rect_edges, rect_faces, segments_cross};
use super::world_file::{
    BlockSpec, GateSpec, ObstacleSpec, Side, WallMarkers, WallSpec, WorldFile,
};
use super::{Block, BlockColor, Gate, Marker, Obstacle, World, WorldError};
use crate::geometry::{Point2, Pose2, Segment, wrap_angle};
use crate::perception::markers::MarkerCategory as Cat;
use std::f64::consts::FRAC_PI_2;
use std::path::Path;

/// Most markers one wall may generate (the largest category holds 300 ids).
const MAX_GENERATED: f64 = 300.0;

/// Checks every rule and assembles the world.
pub fn build(file: WorldFile, text: &str, path: &Path) -> Result<World, WorldError> {
    let mut ck = Checker::new(text, path);
    let name_line = ck.line(file.name.span());
    let name = file.name.into_inner();
    if name.trim().is_empty() {
        return Err(ck.err(name_line, "name", "\"\"", "must not be empty"));
    }
    if name.chars().any(char::is_control) || name.chars().count() > MAX_NAME {
        let shown = crate::data::printable::printable(&name, Some(40));
        let reason = format!(
            "must be at most {MAX_NAME} characters, none of them control characters (it is shown in the terminal)"
        );
        return Err(ck.err(name_line, "name", format!("{shown:?}"), reason));
    }
    let size_line = ck.line(file.size.span());
    let [width, height] = *file.size.get_ref();
    for (field, v) in [("size[0]", width), ("size[1]", height)] {
        ck.positive(size_line, field, v)?;
        if !(MIN_WORLD_SIDE..=MAX_WORLD_SIDE).contains(&v) {
            return Err(ck.err(
                size_line,
                field,
                crate::data::number::short(v),
                format!("must lie in {MIN_WORLD_SIDE}..={MAX_WORLD_SIDE} m"),
            ));
        }
    }
    ck.set_bounds(width, height);
    let start_line = ck.line(file.start.span());
    let [sx, sy, sdeg] = *file.start.get_ref();
    ck.finite(start_line, "start", &[sx, sy, sdeg])?;
    ck.inside(start_line, "start", Point2::new(sx, sy))?;
    let start = Pose2::new(sx, sy, wrap_angle(sdeg.to_radians()));

    let mut world = World {
        name,
        width,
        height,
        start,
        walls: Vec::new(),
        markers: Vec::new(),
        blocks: Vec::new(),
        gates: Vec::new(),
        obstacles: Vec::new(),
        track: None,
    };
    for (i, wall) in file.walls.iter().enumerate() {
        let line = ck.line(wall.span());
        add_wall(&mut ck, &mut world, i, line, wall.get_ref())?;
    }
    for (i, obstacle) in file.obstacles.iter().enumerate() {
        let line = ck.line(obstacle.span());
        add_obstacle(&mut ck, &mut world, i, line, obstacle.get_ref())?;
    }
    for (i, m) in file.markers.iter().enumerate() {
        let (line, m, field) = (ck.line(m.span()), m.get_ref(), format!("markers[{i}]"));
        ck.finite(line, &field, &[m.x, m.y, m.facing_deg])?;
        ck.inside(line, &format!("{field}.x/y"), Point2::new(m.x, m.y))?;
        ck.category(
            line,
            &format!("{field}.id"),
            m.id,
            &[Cat::Boundary, Cat::Obstacle],
        )?;
        ck.claim(line, &format!("{field}.id"), m.id)?;
        let normal = wrap_angle(m.facing_deg.to_radians());
        world.markers.push(Marker {
            id: m.id,
            position: Point2::new(m.x, m.y),
            normal,
        });
    }
    for (i, gate) in file.gates.iter().enumerate() {
        let line = ck.line(gate.span());
        add_gate(&mut ck, &mut world, i, line, gate.get_ref())?;
    }
    for (i, block) in file.blocks.iter().enumerate() {
        let line = ck.line(block.span());
        add_block(&mut ck, &mut world, i, line, block.get_ref())?;
    }
    if let Some(why) = world.start_conflict(START_CLEARANCE) {
        let reason = format!("the robot's centre {why}");
        return Err(ck.err(start_line, "start", fmt_numbers(&[sx, sy, sdeg]), reason));
    }
    if let Some(spec) = &file.track {
        let line = ck.line(spec.span());
        let scene = spec.get_ref().build().map_err(|e| {
            ck.err(
                line,
                &format!("track.{}", e.field),
                &e.value,
                e.reason.clone(),
            )
        })?;
        if let Some(p) = (scene.track.points().iter()).find(|p| !world.contains(**p)) {
            let at = format!("[{:.2}, {:.2}]", p.x, p.y);
            return Err(ck.err(line, "track.points", at, "the lane leaves the world"));
        }
        world.walls.extend(scene.post_outlines());
        world.track = Some(Box::new(scene));
    }
    check_blocks_apart(&ck, &world, &file.blocks)?;
    check_gates_on_walls(&ck, &world, &file.gates)?;
    Ok(world)
}

/// Most characters of a world's name.
const MAX_NAME: usize = 80;
/// Least distance from the start point to any wall, metres: the robot's centre cannot
/// stand on one (the config's footprint is checked against the world at session start).
const START_CLEARANCE: f64 = 0.01;
/// Smallest world side accepted, metres: no robot fits in less.
const MIN_WORLD_SIDE: f64 = 0.5;
/// How far a gate's centre may be from the wall it sits on, metres.
const GATE_ON_WALL: f64 = 0.1;

/// Blocks stand free: none inside an obstacle, through a wall, or overlapping another.
fn check_blocks_apart(
    ck: &Checker,
    world: &World,
    specs: &[toml::Spanned<BlockSpec>],
) -> Result<(), WorldError> {
    for (i, b) in world.blocks.iter().enumerate() {
        let line = specs.get(i).and_then(|s| ck.line(s.span()));
        let field = format!("blocks[{i}]");
        let at = fmt_point(b.pose.position());
        let corners = rect_corners(b.pose, b.size, b.size);
        for (k, o) in world.obstacles.iter().enumerate() {
            if corners
                .iter()
                .chain([&b.pose.position()])
                .any(|&c| rect_contains(o.pose, o.width, o.height, c))
            {
                return Err(ck.err(line, &field, &at, format!("lies inside obstacles[{k}]")));
            }
        }
        let edges = rect_edges(b.pose, b.size, b.size);
        if world
            .walls
            .iter()
            .any(|w| edges.iter().any(|e| segments_cross(e.a, e.b, w.a, w.b)))
        {
            return Err(ck.err(line, &field, &at, "crosses a wall"));
        }
        for (j, other) in world.blocks.iter().enumerate().take(i) {
            let overlap = rect_corners(other.pose, other.size, other.size)
                .iter()
                .chain([&other.pose.position()])
                .any(|&c| rect_contains(b.pose, b.size, b.size, c))
                || corners
                    .iter()
                    .chain([&b.pose.position()])
                    .any(|&c| rect_contains(other.pose, other.size, other.size, c));
            if overlap {
                return Err(ck.err(line, &field, &at, format!("overlaps blocks[{j}]")));
            }
        }
    }
    Ok(())
}

/// A gate's markers are on a wall: its centre within `GATE_ON_WALL` of one.
fn check_gates_on_walls(
    ck: &Checker,
    world: &World,
    specs: &[toml::Spanned<GateSpec>],
) -> Result<(), WorldError> {
    for (i, gate) in world.gates.iter().enumerate() {
        let Some(pose) = world.gate_pose(gate) else {
            continue;
        };
        let nearest = world
            .walls
            .iter()
            .map(|w| w.distance_to(pose.position()))
            .fold(f64::INFINITY, f64::min);
        if nearest > GATE_ON_WALL {
            let line = specs.get(i).and_then(|s| ck.line(s.span()));
            let reason = format!(
                "is {nearest:.2} m from the nearest wall: a gate's markers hang on a wall (within {GATE_ON_WALL} m)"
            );
            return Err(ck.err(
                line,
                &format!("gates[{i}].center"),
                fmt_point(pose.position()),
                reason,
            ));
        }
    }
    Ok(())
}

/// A polyline wall: its segments join `world.walls`, its generated markers `world.markers`.
fn add_wall(
    ck: &mut Checker,
    world: &mut World,
    i: usize,
    line: Option<usize>,
    wall: &WallSpec,
) -> Result<(), WorldError> {
    let field = format!("walls[{i}]");
    let need = if wall.closed { 3 } else { 2 };
    if wall.points.len() < need {
        let reason = format!(
            "{} wall needs at least {need} points",
            if wall.closed { "a closed" } else { "an open" }
        );
        return Err(ck.err(
            line,
            &format!("{field}.points"),
            format!("{} point(s)", wall.points.len()),
            reason,
        ));
    }
    let points: Vec<Point2> = wall
        .points
        .iter()
        .map(|p| Point2::new(p[0], p[1]))
        .collect();
    for (k, p) in points.iter().enumerate() {
        ck.inside(line, &format!("{field}.points[{k}]"), *p)?;
    }
    let ends = if wall.closed {
        points.len()
    } else {
        points.len() - 1
    };
    let segments: Vec<Segment> = (0..ends)
        .map(|k| Segment::new(points[k], points[(k + 1) % points.len()]))
        .collect();
    for (k, s) in segments.iter().enumerate() {
        if s.length() < 1e-9 {
            let value = fmt_point(s.a);
            let reason = format!("repeats the point before it: segment {k} has zero length");
            return Err(ck.err(
                line,
                &format!("{field}.points[{}]", (k + 1) % points.len()),
                value,
                reason,
            ));
        }
    }
    if let Some(spec) = &wall.markers {
        generate_markers(
            ck,
            world,
            &format!("{field}.markers"),
            line,
            spec,
            &segments,
        )?;
    }
    world.walls.extend(segments);
    Ok(())
}

/// Markers every `spacing` metres along each segment, centred on it (at least one per
/// segment), facing the segment's left side (CCW boundary: the interior), its right, or both.
fn generate_markers(
    ck: &mut Checker,
    world: &mut World,
    field: &str,
    line: Option<usize>,
    spec: &WallMarkers,
    segments: &[Segment],
) -> Result<(), WorldError> {
    ck.positive(line, &format!("{field}.spacing"), spec.spacing)?;
    let sides: &[f64] = match spec.side {
        Side::Left => &[FRAC_PI_2],
        Side::Right => &[-FRAC_PI_2],
        Side::Both => &[FRAC_PI_2, -FRAC_PI_2],
    };
    let per_segment: Vec<f64> = segments
        .iter()
        .map(|s| (s.length() / spec.spacing + 1e-9).floor().max(1.0))
        .collect();
    let total = per_segment.iter().sum::<f64>() * sides.len() as f64;
    let first_field = format!("{field}.first_id");
    let cat = ck.category(
        line,
        &first_field,
        spec.first_id,
        &[Cat::Boundary, Cat::Obstacle],
    )?;
    let last = spec.first_id as f64 + total - 1.0;
    if total > MAX_GENERATED {
        let reason = format!(
            "spacing {} gives more than {MAX_GENERATED} markers, which run past the {} range",
            spec.spacing,
            cat.label()
        );
        return Err(ck.err(line, &first_field, spec.first_id, reason));
    }
    if Cat::of(last as u32) != cat {
        let reason = format!(
            "the wall generates {total} markers, ids {}..={last}, which run past the {} range",
            spec.first_id,
            cat.label()
        );
        return Err(ck.err(line, &first_field, spec.first_id, reason));
    }
    let mut id = spec.first_id;
    for (s, &n) in segments.iter().zip(&per_segment) {
        let len = s.length();
        let (ux, uy) = ((s.b.x - s.a.x) / len, (s.b.y - s.a.y) / len);
        let heading = uy.atan2(ux);
        let first = (len - (n - 1.0) * spec.spacing) / 2.0;
        for k in 0..n as usize {
            let d = first + k as f64 * spec.spacing;
            let position = Point2::new(s.a.x + ux * d, s.a.y + uy * d);
            for side in sides {
                ck.claim(line, field, id)?;
                world.markers.push(Marker {
                    id,
                    position,
                    normal: wrap_angle(heading + side),
                });
                id += 1;
            }
        }
    }
    Ok(())
}

fn add_obstacle(
    ck: &mut Checker,
    world: &mut World,
    i: usize,
    line: Option<usize>,
    o: &ObstacleSpec,
) -> Result<(), WorldError> {
    let field = format!("obstacles[{i}]");
    ck.finite(line, &format!("{field}.center"), &o.center)?;
    ck.positive(line, &format!("{field}.size[0]"), o.size[0])?;
    ck.positive(line, &format!("{field}.size[1]"), o.size[1])?;
    ck.finite(line, &format!("{field}.yaw_deg"), &[o.yaw_deg])?;
    let pose = Pose2::new(o.center[0], o.center[1], wrap_angle(o.yaw_deg.to_radians()));
    for (k, c) in rect_corners(pose, o.size[0], o.size[1])
        .into_iter()
        .enumerate()
    {
        ck.inside(line, &format!("{field} corner {k}"), c)?;
    }
    if o.markers.len() > 4 {
        let reason =
            "a box has four faces (+x, +y, -x, -y): give at most four ids, 0 for a bare face";
        return Err(ck.err(
            line,
            &format!("{field}.markers"),
            fmt_list(&o.markers),
            reason,
        ));
    }
    let faces = rect_faces(pose, o.size[0], o.size[1]);
    for (k, &id) in o.markers.iter().enumerate().filter(|(_, id)| **id != 0) {
        let f = format!("{field}.markers[{k}]");
        ck.category(line, &f, id, &[Cat::Obstacle])?;
        ck.claim(line, &f, id)?;
        world.markers.push(Marker {
            id,
            position: faces[k].0,
            normal: wrap_angle(faces[k].1),
        });
    }
    world.walls.extend(rect_edges(pose, o.size[0], o.size[1]));
    world.obstacles.push(Obstacle {
        pose,
        width: o.size[0],
        height: o.size[1],
    });
    Ok(())
}

/// Gate markers `width` apart across `center`: markers[0] on the left and markers[1] on the
/// right as seen from the arena looking at the gate (i.e. looking along -facing).
fn add_gate(
    ck: &mut Checker,
    world: &mut World,
    i: usize,
    line: Option<usize>,
    g: &GateSpec,
) -> Result<(), WorldError> {
    let field = format!("gates[{i}]");
    ck.finite(line, &format!("{field}.center"), &g.center)?;
    ck.finite(line, &format!("{field}.facing_deg"), &[g.facing_deg])?;
    ck.positive(line, &format!("{field}.width"), g.width)?;
    let want = match g.color {
        BlockColor::Red => Cat::RedGate,
        BlockColor::Blue => Cat::BlueGate,
    };
    if g.markers[0] == g.markers[1] {
        let reason = "a gate needs two different marker ids";
        return Err(ck.err(
            line,
            &format!("{field}.markers"),
            fmt_list(&g.markers),
            reason,
        ));
    }
    let normal = wrap_angle(g.facing_deg.to_radians());
    let (s, c) = (normal + FRAC_PI_2).sin_cos();
    for (k, &id) in g.markers.iter().enumerate() {
        let f = format!("{field}.markers[{k}]");
        ck.category(line, &f, id, &[want])?;
        let offset = if k == 0 {
            -g.width / 2.0
        } else {
            g.width / 2.0
        };
        let position = Point2::new(g.center[0] + c * offset, g.center[1] + s * offset);
        ck.inside(line, &format!("{f} position"), position)?;
        ck.claim(line, &f, id)?;
        world.markers.push(Marker {
            id,
            position,
            normal,
        });
    }
    world.gates.push(Gate {
        color: g.color,
        markers: g.markers,
    });
    Ok(())
}

fn add_block(
    ck: &mut Checker,
    world: &mut World,
    i: usize,
    line: Option<usize>,
    b: &BlockSpec,
) -> Result<(), WorldError> {
    let field = format!("blocks[{i}]");
    ck.finite(
        line,
        &format!("{field}.x/y/yaw_deg"),
        &[b.x, b.y, b.yaw_deg],
    )?;
    ck.positive(line, &format!("{field}.size"), b.size)?;
    let want = match b.color {
        BlockColor::Red => Cat::RedBlock,
        BlockColor::Blue => Cat::BlueBlock,
    };
    let mfield = format!("{field}.markers");
    ck.category(line, &format!("{mfield}[0]"), b.markers[0], &[want])?;
    ck.category(line, &format!("{mfield}[1]"), b.markers[1], &[want])?;
    if b.markers[0].is_multiple_of(2) || b.markers[1] != b.markers[0] + 1 {
        let reason = "a block carries an odd id n (local +x face) and n + 1 (local +y face), e.g. [421, 422]";
        return Err(ck.err(line, &mfield, fmt_list(&b.markers), reason));
    }
    let pose = Pose2::new(b.x, b.y, wrap_angle(b.yaw_deg.to_radians()));
    for (k, c) in rect_corners(pose, b.size, b.size).into_iter().enumerate() {
        ck.inside(line, &format!("{field} corner {k}"), c)?;
    }
    ck.claim(line, &format!("{mfield}[0]"), b.markers[0])?;
    ck.claim(line, &format!("{mfield}[1]"), b.markers[1])?;
    world.blocks.push(Block {
        color: b.color,
        pose,
        size: b.size,
        markers: b.markers,
    });
    Ok(())
}
