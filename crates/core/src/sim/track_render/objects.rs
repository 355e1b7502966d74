//! What stands on the floor, as flat faces for the depth-buffered fill: the world's walls,
//! box obstacles, the traffic lights (post, housing, three lamps) and the barriers (post
//! and a striped arm raised by its cycle).

use super::palette::{self, Hsv};
use super::raster::Face;
use crate::data::LightColour;
use crate::geometry::{Pose2, Segment};
use crate::sim::track::{
    ARM_HEIGHT, ARM_THICKNESS, Barrier, LAMP_HEIGHT, LAMP_RADIUS, POST, TrackScene, TrafficLight,
    lamp_height,
};
use nalgebra::Vector3;

/// Height of the world's walls, metres.
pub const WALL_HEIGHT: f64 = 0.3;
/// Height of box obstacles, metres.
pub const BOX_HEIGHT: f64 = 0.15;
/// A light's housing: depth, width and height, metres.
const HOUSING: [f64; 3] = [0.04, 0.06, 0.16];
/// Length of each red or white stripe of a barrier's arm, metres.
const STRIPE: f64 = 0.1;
/// Sides of the polygon a lamp is drawn as.
const LAMP_SIDES: usize = 20;
/// How far a lamp stands proud of its housing's face, and a lit lamp's bright centre of
/// the lamp, metres, so the depth buffer keeps each in front.
const PROUD: f64 = 0.001;
/// The lit lamp's bright centre, as a fraction of its radius.
const CORE: f64 = 0.55;
/// How little an emissive lamp follows the scene's brightness: brightness^0.2.
const EMISSIVE_EXPONENT: f64 = 0.2;
/// Direction the room's light comes from, for shading the sides of solids.
const SUN: [f64; 2] = [0.6, 0.8];

/// The faces of everything standing in the scene at twin time `t`, lit by `brightness`.
pub fn faces(
    scene: &TrackScene,
    walls: &[Segment],
    boxes: &[(Pose2, f64, f64)],
    t: f64,
    brightness: f64,
    out: &mut Vec<Face>,
) {
    let wall = palette::bgr(palette::WALL);
    for w in walls {
        let (a, b) = (w.a, w.b);
        let along = Vector3::new(b.x - a.x, b.y - a.y, 0.0);
        let normal = Vector3::new(-along.y, along.x, 0.0);
        out.push(Face {
            points: vec![
                Vector3::new(a.x, a.y, 0.0),
                Vector3::new(b.x, b.y, 0.0),
                Vector3::new(b.x, b.y, WALL_HEIGHT),
                Vector3::new(a.x, a.y, WALL_HEIGHT),
            ],
            bgr: palette::bytes(wall, brightness * side_shade(normal)),
            outward: None,
        });
    }
    for &(pose, width, depth) in boxes {
        let (s, c) = pose.theta.sin_cos();
        let axes = [
            Vector3::new(c, s, 0.0) * width / 2.0,
            Vector3::new(-s, c, 0.0) * depth / 2.0,
            Vector3::z() * BOX_HEIGHT / 2.0,
        ];
        let centre = Vector3::new(pose.x, pose.y, BOX_HEIGHT / 2.0);
        cuboid(centre, axes, palette::BOX, brightness, [true, true], out);
    }
    for light in &scene.lights {
        traffic_light(light, t, brightness, out);
    }
    for barrier in &scene.barriers {
        barrier_faces(barrier, t, brightness, out);
    }
}

/// Shade of a face of outward normal `n`: tops full, sides by how squarely they face
/// the room's light (Lambert's cosine law, with ambient light to fill).
fn side_shade(n: Vector3<f64>) -> f64 {
    let len = n.norm().max(1e-12);
    if n.z / len > 0.5 {
        return 1.0;
    }
    let (x, y) = (n.x / len, n.y / len);
    0.8 + 0.2 * (x * SUN[0] + y * SUN[1]).abs()
}

/// The six faces of a box of centre `centre` and half-axes `axes` (the first axis's two
/// end faces only where `caps` says).
fn cuboid(
    centre: Vector3<f64>,
    axes: [Vector3<f64>; 3],
    colour: Hsv,
    brightness: f64,
    caps: [bool; 2],
    out: &mut Vec<Face>,
) {
    let bgr = palette::bgr(colour);
    for k in 0..3 {
        let (a, b, e) = (axes[k], axes[(k + 1) % 3], axes[(k + 2) % 3]);
        for (sign, cap) in [(1.0, caps[1]), (-1.0, caps[0])] {
            if k == 0 && !cap {
                continue;
            }
            let c = centre + a * sign;
            out.push(Face {
                points: vec![c - b - e, c + b - e, c + b + e, c - b + e],
                bgr: palette::bytes(bgr, brightness * side_shade(a * sign)),
                outward: Some(a * sign),
            });
        }
    }
}

/// A disc of `radius` centred at `centre` in the vertical plane facing `facing`.
fn disc(centre: Vector3<f64>, facing: Vector3<f64>, radius: f64, bgr: [u8; 3]) -> Face {
    let side = Vector3::new(-facing.y, facing.x, 0.0);
    let points = (0..LAMP_SIDES)
        .map(|i| {
            let a = i as f64 * std::f64::consts::TAU / LAMP_SIDES as f64;
            centre + side * (radius * a.cos()) + Vector3::z() * (radius * a.sin())
        })
        .collect();
    Face {
        points,
        bgr,
        outward: Some(facing),
    }
}

/// The hue a lit lamp of `colour` shows.
pub fn lamp_hue(colour: LightColour) -> f64 {
    match colour {
        LightColour::Red => palette::LAMP_RED_HUE,
        LightColour::Yellow => palette::LAMP_YELLOW_HUE,
        LightColour::Green => palette::LAMP_GREEN_HUE,
    }
}

/// The centre of `light`'s lamp of `colour`, on its housing's face.
pub fn lamp_centre(light: &TrafficLight, colour: LightColour) -> Vector3<f64> {
    let (s, c) = light.facing.sin_cos();
    let front = HOUSING[0] / 2.0 + PROUD;
    Vector3::new(
        light.position.x + c * front,
        light.position.y + s * front,
        lamp_height(colour),
    )
}

fn traffic_light(light: &TrafficLight, t: f64, brightness: f64, out: &mut Vec<Face>) {
    let (s, c) = light.facing.sin_cos();
    let (facing, side) = (Vector3::new(c, s, 0.0), Vector3::new(-s, c, 0.0));
    let base = Vector3::new(light.position.x, light.position.y, 0.0);
    let housing_bottom = LAMP_HEIGHT - HOUSING[2] / 2.0;
    let post = [
        facing * POST / 2.0,
        side * POST / 2.0,
        Vector3::z() * housing_bottom / 2.0,
    ];
    let post_centre = base + Vector3::z() * housing_bottom / 2.0;
    cuboid(
        post_centre,
        post,
        palette::LIGHT_POST,
        brightness,
        [true, true],
        out,
    );
    let half = HOUSING.map(|v| v / 2.0);
    let housing = [facing * half[0], side * half[1], Vector3::z() * half[2]];
    let housing_centre = base + Vector3::z() * LAMP_HEIGHT;
    cuboid(
        housing_centre,
        housing,
        palette::HOUSING,
        brightness,
        [true, true],
        out,
    );
    let lit = light.cycle.colour_at(t);
    let glow = brightness.powf(EMISSIVE_EXPONENT);
    for colour in LightColour::ALL {
        let centre = lamp_centre(light, colour);
        let h = lamp_hue(colour);
        if colour == lit {
            let (s, v) = palette::LAMP_RIM_SV;
            let rim = palette::bytes(palette::bgr(Hsv { h, s, v }), glow);
            out.push(disc(centre, facing, LAMP_RADIUS, rim));
            let (s, v) = palette::LAMP_CORE_SV;
            let core = palette::bytes(palette::bgr(Hsv { h, s, v }), glow);
            out.push(disc(
                centre + facing * PROUD,
                facing,
                LAMP_RADIUS * CORE,
                core,
            ));
        } else {
            let (s, v) = palette::LAMP_OFF_SV;
            let dull = palette::bytes(palette::bgr(Hsv { h, s, v }), brightness);
            out.push(disc(centre, facing, LAMP_RADIUS, dull));
        }
    }
}

/// The unit vector along `barrier`'s arm raised `angle` above level.
pub fn arm_direction(barrier: &Barrier, angle: f64) -> Vector3<f64> {
    let (s, c) = barrier.across.sin_cos();
    Vector3::new(c * angle.cos(), s * angle.cos(), angle.sin())
}

fn barrier_faces(barrier: &Barrier, t: f64, brightness: f64, out: &mut Vec<Face>) {
    let (s, c) = barrier.across.sin_cos();
    let (across, side) = (Vector3::new(c, s, 0.0), Vector3::new(-s, c, 0.0));
    let pivot = Vector3::new(barrier.pivot.x, barrier.pivot.y, ARM_HEIGHT);
    let post = [
        across * POST / 2.0,
        side * POST / 2.0,
        Vector3::z() * ARM_HEIGHT / 2.0,
    ];
    let post_centre = Vector3::new(barrier.pivot.x, barrier.pivot.y, ARM_HEIGHT / 2.0);
    cuboid(
        post_centre,
        post,
        palette::BARRIER_POST,
        brightness,
        [true, true],
        out,
    );
    // The arm turns about the horizontal axis `side` through the pivot, in the vertical
    // plane that contains `across`.
    let dir = arm_direction(barrier, barrier.angle_at(t));
    let normal = dir.cross(&side);
    let stripes = (barrier.span / STRIPE).ceil().max(1.0) as usize;
    for k in 0..stripes {
        let r0 = k as f64 * STRIPE;
        let r1 = ((k + 1) as f64 * STRIPE).min(barrier.span);
        if r1 <= r0 {
            break;
        }
        let axes = [
            dir * (r1 - r0) / 2.0,
            side * ARM_THICKNESS / 2.0,
            normal * ARM_THICKNESS / 2.0,
        ];
        let colour = if k % 2 == 0 {
            palette::ARM_RED
        } else {
            palette::ARM_WHITE
        };
        let caps = [k == 0, k + 1 == stripes];
        cuboid(
            pivot + dir * (r0 + r1) / 2.0,
            axes,
            colour,
            brightness,
            caps,
            out,
        );
    }
}
