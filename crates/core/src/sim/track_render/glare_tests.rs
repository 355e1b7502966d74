//! The glare painted row by row, between each ellipse's edges, is the glare of every lamp
//! tried on every pixel of its box.
use super::*;
use crate::perception::lane_camera::LaneCameraConfig;
use rand::SeedableRng;

/// Each lamp in turn, every pixel of its box tested against its ellipse.
fn paint_pixel_by_pixel(ceiling: &Ceiling, rays: &FloorRays, view: &View, pose: Pose2) -> Vec<u8> {
    let mut out = background(view);
    for spot in (ceiling.lamps.iter()).filter_map(|lamp| Spot::of(lamp, view, pose)) {
        for y in spot.rows.0..spot.rows.1 {
            for x in spot.cols.0..spot.cols.1 {
                let i = y * view.width + x;
                paint_pixel(&spot, rays, i, &mut out[3 * i..3 * i + 3]);
            }
        }
    }
    out
}

/// Blends the glare into pixel `i` (`px`, its BGR bytes) on its own, each channel as the
/// stretch does all of them, if its floor point is inside the ellipse.
fn paint_pixel(spot: &Spot, rays: &FloorRays, i: usize, px: &mut [u8]) {
    let Some(w) = rays.point(i).map(|p| spot.weight(p)).filter(|&w| w > 0.0) else {
        return;
    };
    for (channel, glare) in px.iter_mut().zip(spot.glare) {
        let v = f32::from(*channel) * (1.0 - w) + glare * w;
        *channel = (v + 0.5).clamp(0.0, 255.0) as u8;
    }
}

/// A frame of every grey level, so a blend shows in every pixel it touches.
fn background(view: &View) -> Vec<u8> {
    (0..3 * view.width * view.height)
        .map(|i| (i * 7 % 251) as u8)
        .collect()
}

#[test]
fn painting_rows_between_the_ellipses_edges_gives_the_glare_of_testing_every_pixel() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let ceiling = Ceiling::new(&mut rng, Point2::new(-4.0, -3.0), Point2::new(4.0, 3.0));
    let mut glared = 0;
    // A level camera, and one rolled: its rows meet the floor in short uneven stretches.
    for roll in [0.0, 8.0] {
        let mut camera = LaneCameraConfig::default();
        camera.mount.rotation_deg[1] = roll;
        let (k, mount) = (camera.intrinsics(), camera.mount());
        let rays = FloorRays::new(&k, &mount, 0.005);
        for _ in 0..40 {
            let pose = Pose2::new(
                rng.random_range(-3.0..3.0),
                rng.random_range(-2.5..2.5),
                rng.random_range(-3.2..3.2),
            );
            let view = View::new(&k, &mount, pose);
            let mut out = background(&view);
            ceiling.paint_glare(&rays, &view, pose, &mut out);
            let want = paint_pixel_by_pixel(&ceiling, &rays, &view, pose);
            let differ = out.iter().zip(&want).filter(|(a, b)| a != b).count();
            assert_eq!(differ, 0, "roll {roll}, {pose:?}");
            glared += (out.iter().zip(background(&view)))
                .filter(|(a, b)| **a != *b)
                .count();
        }
    }
    // The frames had glare in them to compare.
    assert!(glared > 10_000, "{glared}");
}
