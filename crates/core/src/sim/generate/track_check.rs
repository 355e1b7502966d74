//! Is a lane track drivable? The bends no tighter than a robot can follow, the lane never
//! coming back near itself, inside the walls, the start on a straight facing along the
//! lane, and the lights and barriers on gentle stretches, apart, with their posts clear
//! of the lane.

use crate::geometry::{Point2, wrap_angle};
use crate::sim::World;
use crate::sim::track::{Track, TrackScene};
use std::collections::HashMap;

/// Tightest bend, metres: a TurtleBot3 AutoRace bend is about 0.5 m (issue 39), and the
/// robot's footprint radius is 0.08 m.
pub const MIN_RADIUS: f64 = 0.45;
/// Curvature is measured between points this many steps either side (0.1 m at the
/// track's 0.02 m step), long enough to average over the resampled polyline's corners.
pub const RADIUS_WINDOW: usize = 5;
/// Two parts of the lane that are not neighbours keep `lane_width` plus this apart,
/// centreline to centreline, metres: room for a post between them.
pub const LANE_GAP: f64 = 0.45;
/// The lane's outer edges keep this far from every wall, metres.
pub const WALL_MARGIN: f64 = 0.3;
/// The start stands on a stretch at least `START_STRETCH` long whose radius is at least
/// `START_RADIUS`, metres: the robot sets off straight.
pub const START_RADIUS: f64 = 1.5;
pub const START_STRETCH: f64 = 0.6;
/// Lights and barriers stand where the radius is at least this within `SIGNAL_REACH`
/// either side, metres: a gentle stretch where the camera sees them ahead.
pub const SIGNAL_RADIUS: f64 = 1.0;
pub const SIGNAL_REACH: f64 = 0.3;
/// Lights and barriers keep this far apart along the lane, metres.
pub const SIGNAL_SPACING: f64 = 1.2;
/// ... and this far along the lane from the start, metres.
pub const SIGNAL_FROM_START: f64 = 1.0;
/// A post keeps this far from the outer edge of every other part of the lane, metres.
pub const POST_CLEARANCE: f64 = 0.25;
/// A post's centre keeps this far from every wall, metres.
pub const POST_WALL_MARGIN: f64 = 0.1;
/// The start lies this close to the centreline and its heading this close to the lane's
/// (metres, radians): the file's rounding and the resampled polyline's corners.
const ON_LANE: f64 = 0.005;
const ALONG_LANE: f64 = 0.02;

/// `Ok` when the world's track is drivable, else the first thing wrong with it.
pub fn check(world: &World) -> Result<(), String> {
    let scene = world.track.as_ref().ok_or("the world has no track")?;
    let track = &scene.track;
    lane(world, track)?;
    let radii = local_radii(track, RADIUS_WINDOW);
    let start_along = start_on_lane(world, track, &radii)?;
    signals(world, scene, &radii, start_along)
}

/// The lane alone: no bend too tight, inside the walls, never back near itself.
pub fn lane(world: &World, track: &Track) -> Result<(), String> {
    let radius = track.min_radius(RADIUS_WINDOW);
    if radius < MIN_RADIUS {
        return Err(format!(
            "a bend of radius {radius:.2} m, under {MIN_RADIUS} m"
        ));
    }
    inside_walls(world, track)?;
    no_bottleneck(track)
}

/// Radius of curvature at each resampled point, from the points `window` steps either
/// side (Menger curvature: the circle through three points has radius abc / 4 area).
pub fn local_radii(track: &Track, window: usize) -> Vec<f64> {
    let p = track.points();
    let n = p.len();
    let w = window.clamp(1, (n / 3).max(1));
    (0..n)
        .map(|i| {
            let (a, b, c) = (p[(i + n - w) % n], p[i], p[(i + w) % n]);
            let area2 = ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)).abs();
            if area2 < 1e-12 {
                f64::INFINITY
            } else {
                a.distance(b) * b.distance(c) * c.distance(a) / (2.0 * area2)
            }
        })
        .collect()
}

/// Distance between two arc lengths round a closed lane of `length`, metres.
pub fn apart(a: f64, b: f64, length: f64) -> f64 {
    let d = (a - b).rem_euclid(length);
    d.min(length - d)
}

/// Half the lane's painted width: centreline to the outer edge of a line, metres.
fn half_width(track: &Track) -> f64 {
    track.lane_width / 2.0 + track.line_width / 2.0
}

fn at(p: Point2) -> String {
    format!("({:.2}, {:.2})", p.x, p.y)
}

/// The world's walls but the track's own posts (which stand in `walls` too).
fn room_walls(world: &World) -> Vec<crate::geometry::Segment> {
    let posts = world
        .track
        .as_ref()
        .map(|t| t.post_outlines())
        .unwrap_or_default();
    (world.walls.iter())
        .filter(|w| !posts.contains(w))
        .copied()
        .collect()
}

fn inside_walls(world: &World, track: &Track) -> Result<(), String> {
    let least = half_width(track) + WALL_MARGIN;
    let walls = room_walls(world);
    for &p in track.points() {
        if !world.contains(p) {
            return Err(format!("the lane at {} leaves the world", at(p)));
        }
        if let Some(d) = (walls.iter().map(|w| w.distance_to(p))).find(|&d| d < least) {
            return Err(format!(
                "the lane's centre at {} is {d:.2} m from a wall, under {least:.2} m",
                at(p)
            ));
        }
    }
    Ok(())
}

/// Two points of the centreline closer than `lane_width + LANE_GAP` must be neighbours:
/// no farther apart along the lane than half round a circle of that diameter (a lane
/// that goes farther and comes back that close has crossed or squeezed itself).
fn no_bottleneck(track: &Track) -> Result<(), String> {
    let gap = track.lane_width + LANE_GAP;
    let neighbours = std::f64::consts::PI * gap / 2.0;
    let points = track.points();
    let step = track.length() / points.len() as f64;
    // Points bucketed in cells `gap` wide: only the 3 x 3 cells round a point can hold
    // one closer than `gap`.
    let cell = |p: Point2| ((p.x / gap).floor() as i64, (p.y / gap).floor() as i64);
    let mut cells: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    for (i, &p) in points.iter().enumerate() {
        cells.entry(cell(p)).or_default().push(i);
    }
    for (i, &p) in points.iter().enumerate() {
        let (cx, cy) = cell(p);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for &j in cells.get(&(cx + dx, cy + dy)).into_iter().flatten() {
                    let d = p.distance(points[j]);
                    let along = apart(i as f64 * step, j as f64 * step, track.length());
                    if j > i && d < gap && along > neighbours {
                        return Err(format!(
                            "the lane at {} comes back within {d:.2} m of itself at {}, under {gap:.2} m",
                            at(p),
                            at(points[j])
                        ));
                    }
                }
            }
        }
    }
    Ok(())
}

/// The start lies on the centreline facing along it, on a straight stretch; its arc
/// length.
fn start_on_lane(world: &World, track: &Track, radii: &[f64]) -> Result<f64, String> {
    let start = world.start.position();
    let here = track.project(start);
    if here.offset.abs() > ON_LANE {
        return Err(format!(
            "the start {} is {:.3} m off the centreline",
            at(start),
            here.offset
        ));
    }
    let turned = wrap_angle(world.start.theta - here.heading).abs();
    if turned > ALONG_LANE {
        return Err(format!(
            "the start faces {:.1} degrees off the lane",
            turned.to_degrees()
        ));
    }
    let straight = straight_run(track, radii, here.along, START_RADIUS);
    if straight < START_STRETCH {
        return Err(format!(
            "the start stands on {straight:.2} m of lane of radius {START_RADIUS} m or more, under {START_STRETCH} m"
        ));
    }
    Ok(here.along)
}

/// Length of the run of points round `along` whose radius is at least `radius`, metres
/// (0 when the point at `along` is tighter).
pub fn straight_run(track: &Track, radii: &[f64], along: f64, radius: f64) -> f64 {
    let n = radii.len();
    let step = track.length() / n as f64;
    let i = ((along / step).round() as usize) % n;
    if radii[i] < radius {
        return 0.0;
    }
    let ahead = (1..n).take_while(|k| radii[(i + k) % n] >= radius).count();
    let behind = (1..n)
        .take_while(|k| radii[(i + n - k) % n] >= radius)
        .count();
    ((ahead + behind + 1).min(n)) as f64 * step
}

/// A light's post stands within this bearing of the lane's heading, radians, seen from the lane's
/// centre anywhere from its stop line to 1 m before it: inside an 80-degree camera's
/// view (the lens 5 cm ahead of the centre sees it within 38.4 degrees at the line) with
/// room for the robot's heading error.
pub const APPROACH_BEARING: f64 = 36.0 * std::f64::consts::PI / 180.0;

/// Whether `post` is ahead within `APPROACH_BEARING` from every point of the lane up to
/// 1 m before `at`: a robot stopping for the light there can see it, and one driving on
/// at green sees it turn until it reaches the line (seed 000's camera-only compliance
/// needs the light in view while the robot waits and while it may still stop; a
/// barrier's arm spans the lane, so it always is).
pub fn seen_on_approach(track: &Track, at: f64, post: Point2) -> bool {
    (0..=10).all(|k| {
        let (p, heading) = track.at((at - 0.1 * f64::from(k)).rem_euclid(track.length()));
        wrap_angle((post.y - p.y).atan2(post.x - p.x) - heading).abs() <= APPROACH_BEARING
    })
}

/// Whether the radius is at least `radius` everywhere within `reach` of `along`.
pub fn gentle(track: &Track, radii: &[f64], along: f64, radius: f64, reach: f64) -> bool {
    let n = radii.len();
    let step = track.length() / n as f64;
    let i = (along / step).round() as i64;
    let k = (reach / step).ceil() as i64;
    (-k..=k).all(|d| radii[(i + d).rem_euclid(n as i64) as usize] >= radius)
}

/// Lights and barriers on gentle stretches, apart from each other and from the start,
/// their posts clear of the lane and of the walls.
fn signals(
    world: &World,
    scene: &TrackScene,
    radii: &[f64],
    start_along: f64,
) -> Result<(), String> {
    let track = &scene.track;
    let length = track.length();
    // A light's post stands LIGHT_BEYOND past its stop line.
    let beyond = crate::sim::track::LIGHT_BEYOND;
    let lights = (scene.lights.iter()).map(|l| ("light", l.along, l.along + beyond, l.position));
    let barriers = (scene.barriers.iter()).map(|b| ("barrier", b.along, b.along, b.pivot));
    let all: Vec<(&str, f64, f64, Point2)> = lights.chain(barriers).collect();
    for (k, &(what, along, post_along, post)) in all.iter().enumerate() {
        let middle = (along + post_along) / 2.0;
        let reach = SIGNAL_REACH + (post_along - along) / 2.0;
        if !gentle(
            track,
            radii,
            middle.rem_euclid(length),
            SIGNAL_RADIUS,
            reach,
        ) {
            return Err(format!(
                "the {what} at {along:.2} m stands where the lane bends tighter than {SIGNAL_RADIUS} m"
            ));
        }
        let from_start = apart(along, start_along, length);
        if from_start < SIGNAL_FROM_START {
            return Err(format!(
                "the {what} at {along:.2} m is {from_start:.2} m from the start, under {SIGNAL_FROM_START} m"
            ));
        }
        if let Some(&(other, at_other, _, _)) = (all[k + 1..].iter())
            .find(|&&(_, other_along, _, _)| apart(along, other_along, length) < SIGNAL_SPACING)
        {
            return Err(format!(
                "the {what} at {along:.2} m and the {other} at {at_other:.2} m are under {SIGNAL_SPACING} m apart"
            ));
        }
        post_clear(world, track, what, post_along.rem_euclid(length), post)?;
    }
    Ok(())
}

/// A post stands off its own stretch of lane and `POST_CLEARANCE` beyond the outer edge
/// of every other part of it, and inside the walls.
pub fn post_clear(
    world: &World,
    track: &Track,
    what: &str,
    along: f64,
    post: Point2,
) -> Result<(), String> {
    let edge = half_width(track);
    let least = edge + POST_CLEARANCE;
    let (own, _) = track.at(along);
    let side = own.distance(post);
    if side <= edge {
        return Err(format!(
            "the {what}'s post at {} stands on the lane, {side:.2} m from its centre",
            at(post)
        ));
    }
    // Beyond this far along, a point of the lane is not the post's own stretch (on a
    // straight it is already `least` from the post).
    let own_stretch = least + side;
    let step = track.length() / track.points().len() as f64;
    for (i, &p) in track.points().iter().enumerate() {
        let d = p.distance(post);
        let other = apart(i as f64 * step, along, track.length()) > own_stretch;
        if d < side - ON_LANE || (other && d < least) {
            return Err(format!(
                "the {what}'s post at {} is {d:.2} m from the lane's centre at {}, under {:.2} m",
                at(post),
                at(p),
                if other { least } else { side }
            ));
        }
    }
    if let Some(d) =
        (room_walls(world).iter().map(|w| w.distance_to(post))).find(|&d| d < POST_WALL_MARGIN)
    {
        return Err(format!(
            "the {what}'s post at {} is {d:.2} m from a wall, under {POST_WALL_MARGIN} m",
            at(post)
        ));
    }
    Ok(())
}
