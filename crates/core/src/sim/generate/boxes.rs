//! Box obstacles: each free-standing with a passage all round, or set against a wall over
//! one of its markers with a passage on its other three sides; never in a gate's lane.

use super::draft::Draft;
use super::draw::{heading, pick, tidy};
use super::rules::{BOX_SIDES, GATE_CLEARANCE, MIN_PASSAGE, TRIES};
use crate::geometry::{Point2, Pose2, wrap_angle};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use std::f64::consts::FRAC_PI_2;

/// How often a box is tried against a wall rather than free-standing.
const AGAINST_WALL: f64 = 0.3;
/// A marker behind a box has its centre this far inside the box's ends, metres: half its
/// 0.10 m square ([vision.markers] boundary_side) and a glance past the edge at the
/// camera's widest 75 degrees off face-on through `WALL_GAP` (0.01 / tan 15 = 0.04 m).
const MARKER_HIDDEN: f64 = 0.1;
/// A marker beside a box stands this far from its end, metres: the mission looks at a
/// marker from 0.3 m in front of it (mission/choose.rs, TARGET_TOO_CLOSE) and a little more.
const MARKER_BESIDE: f64 = 0.35;
/// Gap between a box and the wall it stands against, metres (too narrow for the robot,
/// wide enough that the box's outline never touches the wall).
const WALL_GAP: f64 = 0.01;

/// A box: pose, width, depth, and the face left bare.
type Placed = (Pose2, f64, f64, Option<usize>);

/// Places `count` boxes.
pub fn place(d: &mut Draft, rng: &mut ChaCha8Rng, count: usize) -> Result<(), String> {
    for i in 0..count {
        let placed = (0..TRIES).find_map(|_| {
            let w = pick(rng, BOX_SIDES.0, BOX_SIDES.1, 0.05)?;
            let h = pick(rng, BOX_SIDES.0, BOX_SIDES.1, 0.05)?;
            if rng.random_bool(AGAINST_WALL) {
                against_wall(d, rng, w, h)
            } else {
                free_standing(d, rng, w, h)
            }
        });
        let Some((pose, w, h, bare)) = placed else {
            return Err(format!(
                "no place for box {} of {count} with a {MIN_PASSAGE} m passage round it",
                i + 1
            ));
        };
        d.add_box(pose, w, h, bare);
    }
    Ok(())
}

/// A box anywhere, clear of everything by a passage.
fn free_standing(d: &Draft, rng: &mut ChaCha8Rng, w: f64, h: f64) -> Option<Placed> {
    let (hw, hh) = (d.world.width / 2.0, d.world.height / 2.0);
    let x = pick(rng, -hw + MIN_PASSAGE, hw - MIN_PASSAGE, 0.01)?;
    let y = pick(rng, -hh + MIN_PASSAGE, hh - MIN_PASSAGE, 0.01)?;
    let pose = Pose2::new(x, y, heading(rng));
    fits(d, pose, w, h, None).then_some((pose, w, h, None))
}

/// A box against a wall, centred over one of its markers and narrow enough to leave the
/// neighbouring markers `MARKER_BESIDE` clear; its face towards the wall is bare.
fn against_wall(d: &Draft, rng: &mut ChaCha8Rng, w: f64, h: f64) -> Option<Placed> {
    let k = d.walls[rng.random_range(0..d.walls.len())];
    let s = d.world.walls[k];
    let len = s.length();
    let (ux, uy) = ((s.b.x - s.a.x) / len, (s.b.y - s.a.y) / len);
    let theta = uy.atan2(ux);
    // The boundary (the first walls drawn) has its inside on the left; an interior wall
    // has two sides.
    let left = k < d.boundary_walls || rng.random_bool(0.5);
    let side = if left { 1.0 } else { -1.0 };
    let face = wrap_angle(theta + side * FRAC_PI_2);
    let spots: Vec<f64> = markers_on(d, k, face).collect();
    if spots.is_empty() {
        return None;
    }
    let along = spots[rng.random_range(0..spots.len())];
    // The neighbouring markers, a marker spacing either side, stay MARKER_BESIDE clear.
    let w = tidy(w.min(2.0 * (d.spacing - MARKER_BESIDE)));
    let out = h / 2.0 + WALL_GAP;
    let centre = Point2::new(
        s.a.x + ux * along - side * uy * out,
        s.a.y + uy * along + side * ux * out,
    );
    let pose = Pose2::new(tidy(centre.x), tidy(centre.y), theta);
    // The face towards the wall: local -y on the wall's left, +y on its right.
    let bare = if left { 3 } else { 1 };
    let span = (along - w / 2.0, along + w / 2.0);
    let ok = d.box_clearance(pose, w, h, None) > 0.0
        && fits(d, pose, w, h, Some(k))
        && markers_on(d, k, face).all(|t| {
            const SLACK: f64 = 1e-9;
            let hidden = t >= span.0 + MARKER_HIDDEN - SLACK && t <= span.1 - MARKER_HIDDEN + SLACK;
            hidden || t <= span.0 - MARKER_BESIDE + SLACK || t >= span.1 + MARKER_BESIDE - SLACK
        });
    ok.then_some((pose, w, h, Some(bare)))
}

/// How far along wall `k` each marker on its face `face` lies (gate markers included).
fn markers_on(d: &Draft, k: usize, face: f64) -> impl Iterator<Item = f64> + '_ {
    let s = d.world.walls[k];
    let len = s.length();
    let (ux, uy) = ((s.b.x - s.a.x) / len, (s.b.y - s.a.y) / len);
    d.world
        .markers
        .iter()
        .filter(move |m| {
            s.distance_to(m.position) < 1e-6 && wrap_angle(m.normal - face).abs() < 1e-6
        })
        .map(move |m| (m.position.x - s.a.x) * ux + (m.position.y - s.a.y) * uy)
}

/// A passage between the box and every wall and box but `host`, and the gate lanes clear.
fn fits(d: &Draft, pose: Pose2, w: f64, h: f64, host: Option<usize>) -> bool {
    if d.box_clearance(pose, w, h, host) < MIN_PASSAGE {
        return false;
    }
    let reach = w.hypot(h) / 2.0;
    d.lane_distance(pose.position()) >= GATE_CLEARANCE + reach
}
