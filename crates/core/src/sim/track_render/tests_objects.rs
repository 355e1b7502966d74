//! Traffic lights, barriers and walls as the lane camera sees them, and the truth it
//! reports of them.

use super::objects::{arm_direction, lamp_centre};
use super::tests::{hsv, on_lane, pixel, renderer, rng, square_world, track_world};
use super::*;
use crate::data::{BarrierState, LightColour};
use crate::sim::track::ARM_HEIGHT;
use nalgebra::Vector3;

/// Whether OpenCV hue `h` (0-179) is within `tolerance` of `target`, round the circle.
fn near_hue(h: f64, target: f64, tolerance: f64) -> bool {
    let d = (h - target).rem_euclid(180.0);
    d.min(180.0 - d) <= tolerance
}

#[test]
fn the_lit_lamp_shows_the_colour_of_its_cycle() {
    let world = track_world();
    let mut r = renderer(&world, Lighting::NORMAL);
    let light = &world.track.as_ref().unwrap().lights[0];
    let pose = on_lane(&world, light.along - 1.0);
    // Red 6 s, green 8 s, yellow 2 s from t = 0 (maps/track.toml).
    for (t, colour, hue) in [
        (1.0, LightColour::Red, 5.0),
        (7.0, LightColour::Green, 65.0),
        (15.0, LightColour::Yellow, 28.0),
    ] {
        assert_eq!(light.cycle.colour_at(t), colour);
        let frame = r.render(pose, t, &mut rng());
        let c = lamp_centre(light, colour);
        let at = r.pixel_of(pose, c.x, c.y, c.z).unwrap();
        let lit = hsv(pixel(&frame, at));
        assert!(
            near_hue(lit.h, hue, 8.0) && lit.s > 150.0 && lit.v > 200.0,
            "{colour:?} {lit:?}"
        );
        // The red lamp is dull when another is lit.
        let red = lamp_centre(light, LightColour::Red);
        let red = hsv(pixel(
            &frame,
            r.pixel_of(pose, red.x, red.y, red.z).unwrap(),
        ));
        assert_eq!(
            red.v > 150.0,
            colour == LightColour::Red,
            "{colour:?} red lamp {red:?}"
        );
        let truth = r.truth(pose, t).light.expect("the light is in view");
        assert_eq!(truth.colour, colour);
        // Range from the lens to the lamp, and its radius f r / range.
        let lens = Vector3::new(
            pose.x + 0.05 * pose.theta.cos(),
            pose.y + 0.05 * pose.theta.sin(),
            0.15,
        );
        assert!((truth.range - (c - lens).norm()).abs() < 1e-9, "{truth:?}");
        assert!(
            (truth.radius_px - 381.36 * 0.025 / truth.range).abs() < 0.01,
            "{truth:?}"
        );
    }
}

/// The square course with a light whose post stands 2 m round (its stop line 1.4 m round,
/// the post at x = 0, 0.35 m right of the lane), red.
fn light_world(wall: bool) -> World {
    let light = "[[track.lights]]\nat = 1.4\nside = -0.35\nsequence = [[\"red\", 100]]\n";
    // A short wall right of the lane, across the line of sight from (-1, -1.5).
    let wall = if wall {
        "[[walls]]\npoints = [[-0.45, -2.2], [-0.45, -1.66]]\n"
    } else {
        ""
    };
    square_world(wall, light)
}

use crate::sim::World;

#[test]
fn a_light_behind_a_wall_or_seen_from_behind_is_neither_drawn_nor_true() {
    let open = light_world(false);
    let light = &open.track.as_ref().unwrap().lights[0];
    let red = lamp_centre(light, LightColour::Red);
    let lamp_hue = |world: &World, pose: Pose2| {
        let mut r = renderer(world, Lighting::NORMAL);
        let at = r.pixel_of(pose, red.x, red.y, red.z).unwrap();
        (
            hsv(pixel(&r.render(pose, 0.0, &mut rng()), at)),
            r.truth(pose, 0.0).light,
        )
    };
    let ahead = Pose2::new(-1.0, -1.5, 0.0);
    let (seen, truth) = lamp_hue(&open, ahead);
    assert!(near_hue(seen.h, 5.0, 8.0) && seen.s > 150.0, "{seen:?}");
    assert_eq!(truth.map(|t| t.colour), Some(LightColour::Red));
    let (hidden, truth) = lamp_hue(&light_world(true), ahead);
    assert!(
        hidden.s < 40.0 && hidden.v > 140.0,
        "the wall's grey: {hidden:?}"
    );
    assert_eq!(truth, None);
    // Past the light, looking back at its back: the housing, dark.
    let (back, truth) = lamp_hue(&open, Pose2::new(1.0, -1.5, std::f64::consts::PI));
    assert!(back.v < 70.0, "{back:?}");
    assert_eq!(truth, None);
}

#[test]
fn a_barrier_arm_is_striped_level_when_down_and_upright_when_up() {
    let world = track_world();
    let mut r = renderer(&world, Lighting::NORMAL);
    let barrier = &world.track.as_ref().unwrap().barriers[0];
    let pose = on_lane(&world, barrier.along - 0.8);
    let pivot = Vector3::new(barrier.pivot.x, barrier.pivot.y, ARM_HEIGHT);
    let image_of = |r: &TrackRenderer, p: Vector3<f64>| r.pixel_of(pose, p.x, p.y, p.z).unwrap();
    // Down 5 s, rising 2, up 6, lowering 2, 3 s into the cycle at t = 0 (maps/track.toml).
    for (t, state) in [(0.0, BarrierState::Down), (7.0, BarrierState::Up)] {
        assert_eq!(barrier.state_at(t), state);
        let frame = r.render(pose, t, &mut rng());
        let dir = arm_direction(barrier, barrier.angle_at(t));
        // Stripes 0.1 m long from the pivot: red, white, red, ...
        let red = hsv(pixel(&frame, image_of(&r, pivot + dir * 0.05)));
        let white = hsv(pixel(&frame, image_of(&r, pivot + dir * 0.15)));
        assert!(
            near_hue(red.h, 178.0, 6.0) && red.s > 170.0,
            "{state:?} red {red:?}"
        );
        assert!(
            white.s < 40.0 && white.v > 160.0,
            "{state:?} white {white:?}"
        );
        let (a, b) = (image_of(&r, pivot), image_of(&r, pivot + dir * 0.2));
        let tilt = (b.1 - a.1).abs().atan2((b.0 - a.0).abs()).to_degrees();
        let truth = r.truth(pose, t).barrier.expect("the barrier is in view");
        assert_eq!(truth.state, state);
        match state {
            BarrierState::Down => assert!(tilt < 15.0, "down, {tilt} degrees in the image"),
            _ => assert!(tilt > 75.0, "up, {tilt} degrees in the image"),
        }
    }
}
