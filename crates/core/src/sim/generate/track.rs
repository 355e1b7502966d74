//! Lane tracks drawn from a seed (`--style track`): a walled world with a closed lane in
//! it, modelled on maps/track.toml's AutoRace-style course (seed 000 §2-§3: straights,
//! bends of different radius, S-bends), with traffic lights and barriers beside it.
//!
//! The centreline is the control polygon of the closed cubic B-spline a `[track]` section
//! describes (`track_shape.rs`). The start goes on a straight, the lights and barriers
//! on gentle stretches, posts on the right. A candidate is written as a
//! world file and read back, and must pass `track_check`; else the next is drawn from the
//! same generator.

use super::draw::{pick, tidy};
use super::rules::MARKER_SPACING;
use super::rules::{ATTEMPTS, TRIES};
use super::track_check::{
    self, SIGNAL_FROM_START, SIGNAL_RADIUS, SIGNAL_REACH, SIGNAL_SPACING, START_RADIUS,
    START_STRETCH, WALL_MARGIN, apart, gentle, local_radii,
};
use super::{Colours, GenerateError, GenerateOptions, read_back, track_shape};
use crate::data::number::short;
use crate::geometry::Pose2;
use crate::sim::World;
use crate::sim::shapes::rect_edges;
use crate::sim::track::{
    BarrierCycleSpec, BarrierSpec, LIGHT_BEYOND, LightCycleSpec, LightSpec, Track, TrackSpec,
    TrafficLight,
};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// World sides drawn when none is asked for, metres: round maps/track.toml's 6 m x 4 m
/// course, from a small room's 4 m to 8 m (issue 39).
const SIDES: (f64, f64) = (4.0, 8.0);
/// The shorter side is at most this, metres, so the course is not one long corridor.
const MAX_SHORT_SIDE: f64 = 6.0;
/// Distance between the centres of the lane's lines, metres (issue 39's range, about
/// maps/track.toml's 0.4 m; a TurtleBot3 Burger is 0.18 m wide).
const LANE_WIDTHS: (f64, f64) = (0.35, 0.5);
/// Painted line widths, metres: 2-3 cm tape (issue 39; seed 000 §2.1.1's lanes are tape).
const LINE_WIDTHS: (f64, f64) = (0.02, 0.03);
/// Dash and gap lengths of a dashed white line, metres (issue 39's range).
const DASHES: (f64, f64) = (0.08, 0.15);
/// Lights and barriers each: 1 or 2 (issue 39).
const SIGNALS: (usize, usize) = (1, 2);
/// A post stands this far beyond the lane's half width on the right, metres.
const POST_SIDES: (f64, f64) = (0.12, 0.2);
/// Light cycles, seconds: red, green, yellow (issue 39's ranges).
const RED: (f64, f64) = (4.0, 8.0);
const GREEN: (f64, f64) = (5.0, 10.0);
const YELLOW: (f64, f64) = (1.5, 3.0);
/// Barrier cycles, seconds: down, rising or lowering, up (issue 39's ranges).
const DOWN: (f64, f64) = (4.0, 8.0);
const MOVING: (f64, f64) = (1.5, 3.0);
const UP: (f64, f64) = (8.0, 12.0);
/// Seconds of a cycle are drawn in steps this long.
const SECONDS_STEP: f64 = 0.5;

/// A track world for `options` (validated): the same options give the same world.
pub fn generate(options: &GenerateOptions) -> Result<World, GenerateError> {
    let mut rng = ChaCha8Rng::seed_from_u64(options.seed);
    let (width, height) = match options.size {
        Some(size) => size,
        None => draw_size(&mut rng),
    };
    let mut reason = String::new();
    for _ in 0..ATTEMPTS {
        let drafted = match candidate(&options.name(), width, height, &mut rng) {
            Ok(world) => world,
            Err(why) => {
                reason = why;
                continue;
            }
        };
        let world = read_back(options, &drafted)?;
        match track_check::check(&world) {
            Ok(()) => return Ok(world),
            Err(why) => reason = why,
        }
    }
    Err(GenerateError::Exhausted {
        seed: options.seed,
        style: options.style,
        attempts: ATTEMPTS,
        reason,
    })
}

impl GenerateOptions {
    /// A track world has no markers and no blocks: options about them are refused
    /// (`blocks` and `obstacles` are not read).
    pub(super) fn validate_track(&self) -> Result<(), GenerateError> {
        let refuse = |option, value: String| {
            Err(GenerateError::Option {
                option,
                value,
                reason: "track worlds have no markers and no blocks".into(),
            })
        };
        if !self.wall_markers {
            return refuse("no-wall-markers", "with track worlds".into());
        }
        if self.marker_spacing != MARKER_SPACING {
            return refuse("marker-spacing", short(self.marker_spacing));
        }
        if self.colours != Colours::Alternating {
            return refuse("colours", self.colours.to_string());
        }
        Ok(())
    }
}

/// Width and height, half a metre apart: the longer side either way round.
fn draw_size(rng: &mut ChaCha8Rng) -> (f64, f64) {
    let long = pick(rng, SIDES.0 + 0.5, SIDES.1, 0.5).unwrap_or(SIDES.1);
    let short = pick(rng, SIDES.0, long.min(MAX_SHORT_SIDE), 0.5).unwrap_or(SIDES.0);
    if rng.random_bool(0.5) {
        (long, short)
    } else {
        (short, long)
    }
}

/// One candidate track world, or why it could not be finished.
fn candidate(name: &str, width: f64, height: f64, rng: &mut ChaCha8Rng) -> Result<World, String> {
    let mut world = World {
        name: name.into(),
        width,
        height,
        start: Pose2::default(),
        walls: rect_edges(Pose2::default(), width, height).to_vec(),
        markers: Vec::new(),
        blocks: Vec::new(),
        gates: Vec::new(),
        obstacles: Vec::new(),
        track: None,
    };
    let lane_width = pick(rng, LANE_WIDTHS.0, LANE_WIDTHS.1, 0.01);
    let line_width = pick(rng, LINE_WIDTHS.0, LINE_WIDTHS.1, 0.005);
    let mut spec = TrackSpec {
        points: Vec::new(),
        shape: "spline".into(),
        lane_width: lane_width.ok_or("no lane width")?,
        line_width: line_width.ok_or("no line width")?,
        white: if rng.random_bool(0.7) {
            "dashed"
        } else {
            "solid"
        }
        .into(),
        dash: pick(rng, DASHES.0, DASHES.1, 0.01).ok_or("no dash")?,
        lights: Vec::new(),
        barriers: Vec::new(),
    };
    let margin = spec.lane_width / 2.0 + spec.line_width / 2.0 + WALL_MARGIN;
    spec.points = track_shape::control_points(rng, width / 2.0 - margin, height / 2.0 - margin);
    let bare = spec.build().map_err(|e| e.to_string())?;
    let track = &bare.track;
    track_check::lane(&world, track)?;
    let radii = local_radii(track, track_check::RADIUS_WINDOW);
    let start_along = start(rng, track, &radii)?;
    let (p, heading) = track.at(start_along);
    world.start = Pose2::new(p.x, p.y, heading);
    place_signals(rng, &world, track, &radii, start_along, &mut spec)?;
    let scene = spec.build().map_err(|e| e.to_string())?;
    // The posts stand in the walls, as a world file's do (`build.rs`).
    world.walls.extend(scene.post_outlines());
    world.track = Some(Box::new(scene));
    Ok(world)
}

/// Arc length of the start: the middle of a straight stretch drawn from those long enough.
fn start(rng: &mut ChaCha8Rng, track: &Track, radii: &[f64]) -> Result<f64, String> {
    let n = radii.len();
    let step = track.length() / n as f64;
    let straight: Vec<bool> = radii.iter().map(|&r| r >= START_RADIUS).collect();
    // Runs begin where a straight point follows a bend; a lane straight all round has none.
    let mut runs = Vec::new();
    for i in (0..n).filter(|&i| straight[i] && !straight[(i + n - 1) % n]) {
        let len = (0..n).take_while(|k| straight[(i + k) % n]).count();
        if len as f64 * step >= START_STRETCH + 2.0 * step {
            runs.push((i + len / 2) % n);
        }
    }
    if runs.is_empty() {
        return Err(format!(
            "no stretch {START_STRETCH} m long of radius {START_RADIUS} m or more for the start"
        ));
    }
    Ok(runs[rng.random_range(0..runs.len())] as f64 * step)
}

/// 1-2 lights and 1-2 barriers on the right of gentle stretches, each apart from the
/// others and the start and its post clear of the lane and the walls.
fn place_signals(
    rng: &mut ChaCha8Rng,
    world: &World,
    track: &Track,
    radii: &[f64],
    start_along: f64,
    spec: &mut TrackSpec,
) -> Result<(), String> {
    let length = track.length();
    let step = length / radii.len() as f64;
    let places: Vec<f64> = (0..radii.len())
        .map(|i| i as f64 * step)
        .filter(|&s| gentle(track, radii, s, SIGNAL_RADIUS, SIGNAL_REACH))
        .filter(|&s| apart(s, start_along, length) >= SIGNAL_FROM_START + 0.01)
        .collect();
    let lights = rng.random_range(SIGNALS.0..=SIGNALS.1);
    let barriers = rng.random_range(SIGNALS.0..=SIGNALS.1);
    let mut taken: Vec<f64> = Vec::new();
    for k in 0..lights + barriers {
        let what = if k < lights { "light" } else { "barrier" };
        let (at, side) = (0..TRIES)
            .find_map(|_| {
                let at = tidy(
                    (*places.get(rng.random_range(0..places.len().max(1)))? * 100.0).floor()
                        / 100.0,
                );
                let beyond = pick(rng, POST_SIDES.0, POST_SIDES.1, 0.01)?;
                let side = -tidy(spec.lane_width / 2.0 + beyond);
                let spaced = taken
                    .iter()
                    .all(|&t| apart(t, at, length) >= SIGNAL_SPACING);
                // A light's post stands LIGHT_BEYOND past its stop line, on a gentle
                // stretch too; a barrier's at its arm.
                let (post, post_along) = if k < lights {
                    let post_along = (at + LIGHT_BEYOND).rem_euclid(length);
                    (
                        TrafficLight::beside(track, at, side, no_cycle()).position,
                        post_along,
                    )
                } else {
                    (
                        TrafficLight::beside(track, at - LIGHT_BEYOND, side, no_cycle()).position,
                        at,
                    )
                };
                let gentle_post = gentle(track, radii, post_along, SIGNAL_RADIUS, SIGNAL_REACH);
                let clear = gentle_post
                    && (k >= lights || track_check::seen_on_approach(track, at, post))
                    && track_check::post_clear(world, track, what, post_along, post).is_ok();
                (spaced && clear).then_some((at, side))
            })
            .ok_or_else(|| format!("no place for a {what} on a gentle stretch"))?;
        taken.push(at);
        if k < lights {
            spec.lights.push(LightSpec {
                at,
                side,
                cycle: Some(light_cycle(rng)),
                sequence: None,
            });
        } else {
            spec.barriers.push(BarrierSpec {
                at,
                side,
                span: None,
                cycle: barrier_cycle(rng),
            });
        }
    }
    Ok(())
}

/// Any light cycle: only the post's position is wanted.
fn no_cycle() -> crate::sim::track::LightCycle {
    crate::sim::track::LightCycle::Sequence(Vec::new())
}

/// Seconds from `range` in half-second steps.
fn seconds(rng: &mut ChaCha8Rng, range: (f64, f64)) -> f64 {
    pick(rng, range.0, range.1, SECONDS_STEP).unwrap_or(range.0)
}

fn light_cycle(rng: &mut ChaCha8Rng) -> LightCycleSpec {
    let (red, green, yellow) = (seconds(rng, RED), seconds(rng, GREEN), seconds(rng, YELLOW));
    let period = red + green + yellow;
    LightCycleSpec {
        red,
        green,
        yellow,
        offset: seconds(rng, (0.0, period - SECONDS_STEP)),
    }
}

fn barrier_cycle(rng: &mut ChaCha8Rng) -> BarrierCycleSpec {
    let (down, moving, up) = (seconds(rng, DOWN), seconds(rng, MOVING), seconds(rng, UP));
    // One cycle: down, rising, up, lowering (track/signals.rs).
    let period = down + 2.0 * moving + up;
    BarrierCycleSpec {
        down,
        moving,
        up,
        offset: seconds(rng, (0.0, period - SECONDS_STEP)),
    }
}
