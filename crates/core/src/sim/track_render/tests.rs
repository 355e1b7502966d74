//! The floor, the tape and the lighting as the lane camera sees them.

use super::palette::{self, Hsv};
use super::*;
use crate::sim::World;
use crate::sim::track::LightingLevel;
use std::path::Path;

/// OpenCV's HSV of a BGR pixel, by hand (its `cvtColor(BGR2HSV)` for 8-bit images:
/// V = max, S = 255 (V - min) / V, H in degrees from the largest channel, halved).
pub fn hsv(p: [u8; 3]) -> Hsv {
    let [b, g, r] = p.map(f64::from);
    let v = r.max(g).max(b);
    let delta = v - r.min(g).min(b);
    let s = if v > 0.0 { 255.0 * delta / v } else { 0.0 };
    let h = if delta == 0.0 {
        0.0
    } else if v == r {
        60.0 * (g - b) / delta
    } else if v == g {
        120.0 + 60.0 * (b - r) / delta
    } else {
        240.0 + 60.0 * (r - g) / delta
    };
    Hsv {
        h: h.rem_euclid(360.0) / 2.0,
        s,
        v,
    }
}

/// The mean BGR over the 3x3 pixels round (`u`, `v`), which takes the noise down to 1.
pub fn pixel(frame: &BgrFrame, (u, v): (f64, f64)) -> [u8; 3] {
    let (x, y) = (u.round() as usize, v.round() as usize);
    let mut sum = [0u32; 3];
    for dy in 0..3 {
        for dx in 0..3 {
            let p = frame.at((x + dx).saturating_sub(1), (y + dy).saturating_sub(1));
            for k in 0..3 {
                sum[k] += u32::from(p[k]);
            }
        }
    }
    sum.map(|s| ((s + 4) / 9) as u8)
}

pub fn track_world() -> World {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../maps/track.toml");
    World::load(Path::new(path)).unwrap()
}

/// A 4 x 3 m square course, corners and all, with the world's `extra` TOML and the
/// track's `track_extra` (lights, barriers).
pub fn square_world(extra: &str, track_extra: &str) -> World {
    let text = format!(
        "name = \"square\"\nsize = [6.0, 5.0]\nstart = [-1.0, -1.5, 0.0]\n\
         [[walls]]\npoints = [[-3.0, -2.5], [3.0, -2.5], [3.0, 2.5], [-3.0, 2.5]]\nclosed = true\n\
         {extra}\n\
         [track]\npoints = [[-2.0, -1.5], [2.0, -1.5], [2.0, 1.5], [-2.0, 1.5]]\n\
         shape = \"polyline\"\nlane_width = 0.4\nline_width = 0.025\nwhite = \"dashed\"\ndash = 0.1\n{track_extra}"
    );
    World::from_toml(&text, Path::new("square.toml")).unwrap()
}

pub fn renderer(world: &World, lighting: Lighting) -> TrackRenderer {
    let boxes: Vec<_> = world
        .obstacles
        .iter()
        .map(|o| (o.pose, o.width, o.height))
        .collect();
    let scene = world.track.as_ref().unwrap();
    TrackRenderer::new(
        scene,
        &world.walls,
        &boxes,
        &LaneCameraConfig::default(),
        lighting,
        7,
    )
}

pub fn rng() -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(3)
}

/// The pose `along` metres round `world`'s lane, heading along it.
pub fn on_lane(world: &World, along: f64) -> Pose2 {
    let (p, heading) = world.track.as_ref().unwrap().track.at(along);
    Pose2::new(p.x, p.y, heading)
}

#[test]
fn the_palette_has_the_seeds_hues() {
    for c in [palette::YELLOW_TAPE, palette::WHITE_TAPE, palette::FLOOR] {
        let back = hsv(palette::bytes(palette::bgr(c), 1.0));
        // Hue is only as good as the bytes let it be on a near-grey.
        let hue_ok = c.s < 100.0 || (back.h - c.h).abs() < 1.0;
        assert!(hue_ok && (back.s - c.s).abs() < 2.0, "{c:?} {back:?}");
        assert!((back.v - c.v).abs() < 1.0, "{c:?} {back:?}");
    }
}

#[test]
fn the_yellow_line_is_yellow_the_lane_grey_and_the_white_line_dashed() {
    let world = square_world("", "");
    let mut r = renderer(&world, Lighting::NORMAL);
    let pose = Pose2::new(-1.5, -1.5, 0.0);
    // Hand-worked: the centreline 0.5 m ahead is 0.45 m ahead of the lens, 0.15 m below
    // it, atan(0.15 / 0.45) = 18.43 degrees down, 1.57 above the 20-degree axis:
    // v = 239.5 - 381.36 tan(1.57 deg) = 229.08, on the middle column u = 319.5.
    let centre = r.pixel_of(pose, -1.0, -1.5, 0.0).unwrap();
    assert!(
        (centre.0 - 319.5).abs() < 1e-6 && (centre.1 - 229.08).abs() < 0.01,
        "{centre:?}"
    );
    let frame = r.render(pose, 0.0, &mut rng());
    let grey = hsv(pixel(&frame, centre));
    assert!(
        grey.s < 40.0 && (95.0..118.0).contains(&grey.v),
        "lane {grey:?}"
    );
    let yellow = hsv(pixel(&frame, r.pixel_of(pose, -1.0, -1.3, 0.0).unwrap()));
    assert!((yellow.h - 25.0).abs() < 4.0, "yellow {yellow:?}");
    assert!(
        yellow.s > 160.0 && (160.0..200.0).contains(&yellow.v),
        "yellow {yellow:?}"
    );
    // The white line's dashes: on for 0.1 m, off for 0.1 m from the lane's start at x = -2.
    let dash = hsv(pixel(&frame, r.pixel_of(pose, -0.95, -1.7, 0.0).unwrap()));
    assert!(
        dash.s < 40.0 && (165.0..200.0).contains(&dash.v),
        "dash {dash:?}"
    );
    let gap = hsv(pixel(&frame, r.pixel_of(pose, -0.85, -1.7, 0.0).unwrap()));
    assert!(
        gap.s < 40.0 && (95.0..118.0).contains(&gap.v),
        "gap {gap:?}"
    );
}

fn mean_value(frame: &BgrFrame) -> f64 {
    let sum: f64 = frame
        .data
        .chunks(3)
        .map(|p| hsv([p[0], p[1], p[2]]).v)
        .sum();
    sum / (frame.width * frame.height) as f64
}

#[test]
fn dark_frames_are_darker_than_normal_and_normal_than_bright() {
    let world = track_world();
    let pose = on_lane(&world, 0.5);
    let means: Vec<f64> = [
        LightingLevel::Dark,
        LightingLevel::Normal,
        LightingLevel::Bright,
    ]
    .into_iter()
    .map(|level| {
        let lighting = Lighting {
            level,
            ..Lighting::NORMAL
        };
        mean_value(&renderer(&world, lighting).render(pose, 0.0, &mut rng()))
    })
    .collect();
    // Brightness 0.5, 1 and 1.2 scale the reflected colours.
    assert!(
        means[0] < 0.6 * means[1] && means[1] < means[2] / 1.1,
        "{means:?}"
    );
}

/// Pixels as bright and pale as seed 000 §2.1.3's reflections: V >= 230, S <= 60.
fn glare_pixels(frame: &BgrFrame) -> usize {
    frame
        .data
        .chunks(3)
        .map(|p| hsv([p[0], p[1], p[2]]))
        .filter(|c| c.v >= 230.0 && c.s <= 60.0)
        .count()
}

#[test]
fn glare_spots_appear_only_under_glare_and_move_with_the_robot() {
    let world = track_world();
    let pose = on_lane(&world, 0.5);
    for name in ["normal", "bright", "bright+shadows"] {
        let mut r = renderer(&world, Lighting::parse(name).unwrap());
        let n = glare_pixels(&r.render(pose, 0.0, &mut rng()));
        assert_eq!(n, 0, "{name}");
    }
    let mut r = renderer(&world, Lighting::parse("glare").unwrap());
    let here = r.render(pose, 0.0, &mut rng());
    assert!(glare_pixels(&here) > 200, "{}", glare_pixels(&here));
    // A spot lies where the mirror path meets the floor, so it slides as the robot moves.
    let there = r.render(on_lane(&world, 0.6), 0.0, &mut rng());
    let moved = here
        .data
        .chunks(3)
        .zip(there.data.chunks(3))
        .filter(|(a, b)| {
            let (a, b) = (hsv([a[0], a[1], a[2]]), hsv([b[0], b[1], b[2]]));
            (a.v >= 230.0 && a.s <= 60.0) != (b.v >= 230.0 && b.s <= 60.0)
        })
        .count();
    assert!(moved > 100, "{moved}");
}

#[test]
fn a_shadow_darkens_the_floor_to_under_half() {
    let world = track_world();
    let mut r = renderer(&world, Lighting::NORMAL);
    // The first shadow is centred on the lane: look at it from 0.6 m back along the lane.
    let shadow = &r.shadows[0];
    let centre = Point2::new(
        shadow.iter().map(|p| p.x).sum::<f64>() / 4.0,
        shadow.iter().map(|p| p.y).sum::<f64>() / 4.0,
    );
    let along = world.track.as_ref().unwrap().track.project(centre).along;
    let pose = on_lane(&world, along - 0.6);
    let at = r.pixel_of(pose, centre.x, centre.y, 0.0).unwrap();
    let plain = hsv(pixel(&r.render(pose, 0.0, &mut rng()), at)).v;
    r.set_lighting(Lighting::parse("shadows").unwrap());
    let shaded = hsv(pixel(&r.render(pose, 0.0, &mut rng()), at)).v;
    // The brief's x0.45, give or take the noise.
    assert!((shaded / plain - 0.45).abs() < 0.06, "{plain} -> {shaded}");
}

#[test]
fn the_same_seed_and_calls_give_the_same_frames() {
    let world = track_world();
    let pose = on_lane(&world, 1.0);
    let lighting = Lighting::parse("dark+shadows+glare").unwrap();
    let a = renderer(&world, lighting).render(pose, 2.0, &mut rng());
    let b = renderer(&world, lighting).render(pose, 2.0, &mut rng());
    assert_eq!(a, b);
    let c = renderer(&world, lighting).render(pose, 2.0, &mut ChaCha8Rng::seed_from_u64(4));
    assert_ne!(a, c, "the noise comes from the generator");
}

#[test]
fn a_robot_standing_still_or_coming_back_sees_what_a_fresh_camera_would() {
    let world = track_world();
    let glare = Lighting::parse("glare").unwrap();
    let (here, there) = (on_lane(&world, 0.5), on_lane(&world, 0.6));
    let mut r = renderer(&world, glare);
    r.render(here, 1.0, &mut rng());
    r.render(there, 2.0, &mut rng());
    r.render(here, 2.5, &mut rng());
    // Standing still since 2.5 s: the floor is the one painted then, the rest is new.
    let fresh = renderer(&world, glare).render(here, 3.0, &mut rng());
    assert_eq!(r.render(here, 3.0, &mut rng()), fresh);
    // The light dims while the robot stands.
    let dark = Lighting::parse("dark+glare").unwrap();
    r.set_lighting(dark);
    let fresh = renderer(&world, dark).render(here, 3.5, &mut rng());
    assert_eq!(r.render(here, 3.5, &mut rng()), fresh);
}
