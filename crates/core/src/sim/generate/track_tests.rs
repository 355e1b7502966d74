//! Generated lane tracks: every seed gives a drivable track that reads back from its file,
//! the ranges hold, seeds differ, and the checks refuse bad hand-made tracks.

use super::track_check::{self, MIN_RADIUS};
use super::{Colours, GenerateError, GenerateOptions, Style, generate};
use crate::geometry::Point2;
use crate::sim::World;
use crate::sim::track::{LightCycle, TrackSpec};
use std::collections::HashSet;
use std::path::Path;

const SEEDS: u64 = 200;

fn options(seed: u64) -> GenerateOptions {
    GenerateOptions {
        seed,
        style: Style::Track,
        ..GenerateOptions::default()
    }
}

fn within(v: f64, (lo, hi): (f64, f64)) -> bool {
    (lo - 1e-9..=hi + 1e-9).contains(&v)
}

#[test]
fn every_seed_gives_a_drivable_track_that_reads_back() {
    let mut files = HashSet::new();
    for seed in 1..=SEEDS {
        let world = generate(&options(seed)).unwrap_or_else(|e| panic!("{e}"));
        track_check::check(&world).unwrap_or_else(|e| panic!("seed {seed}: {e}"));
        let text = world.to_toml();
        let back = World::from_toml(&text, Path::new("track.toml")).unwrap();
        assert_eq!(back, world, "seed {seed} reads back");
        assert!(back.track.is_some(), "seed {seed}");
        files.insert(text);
        // No blocks, gates, boxes or markers: a walled room, the lane and its posts.
        assert!(world.blocks.is_empty() && world.gates.is_empty() && world.markers.is_empty());
        let posts = world.track.as_ref().unwrap().posts().len();
        assert_eq!(world.walls.len(), 4 + 4 * posts, "seed {seed}");
    }
    assert_eq!(files.len(), SEEDS as usize, "every seed its own track");
}

#[test]
fn the_drawn_figures_lie_in_their_ranges() {
    let (mut dashed, mut solid, mut turns) = (0, 0, HashSet::new());
    for seed in 1..=SEEDS {
        let world = generate(&options(seed)).unwrap();
        let scene = world.track.as_ref().unwrap();
        let spec = &scene.spec;
        assert!(within(world.width, (4.0, 8.0)) && within(world.height, (4.0, 8.0)));
        assert!(within(spec.lane_width, (0.35, 0.5)), "{}", spec.lane_width);
        assert!(within(spec.line_width, (0.02, 0.03)), "{}", spec.line_width);
        assert!(within(spec.dash, (0.08, 0.15)), "{}", spec.dash);
        assert!((8..=16).contains(&spec.points.len()));
        assert_eq!(spec.shape, "spline");
        match spec.white.as_str() {
            "dashed" => dashed += 1,
            _ => solid += 1,
        }
        assert!((1..=2).contains(&scene.lights.len()) && (1..=2).contains(&scene.barriers.len()));
        let sides = spec.lights.iter().map(|l| l.side);
        for side in sides.chain(spec.barriers.iter().map(|b| b.side)) {
            let beyond = -side - spec.lane_width / 2.0;
            assert!(within(beyond, (0.12, 0.2)), "seed {seed}: side {side}");
        }
        for light in &scene.lights {
            let LightCycle::Periodic {
                red,
                green,
                yellow,
                offset,
            } = light.cycle
            else {
                panic!("seed {seed}: a light without a cycle");
            };
            assert!(within(red, (4.0, 8.0)) && within(green, (5.0, 10.0)));
            assert!(within(yellow, (1.5, 3.0)));
            assert!(within(offset, (0.0, red + green + yellow)));
        }
        for barrier in &scene.barriers {
            let c = barrier.cycle;
            assert!(within(c.down, (4.0, 8.0)) && within(c.moving, (1.5, 3.0)));
            assert!(within(c.up, (8.0, 12.0)));
            assert!(within(c.offset, (0.0, c.down + 2.0 * c.moving + c.up)));
        }
        assert!(scene.track.min_radius(track_check::RADIUS_WINDOW) >= MIN_RADIUS);
        // Which way round the lane is driven: the sign of its area (shoelace formula).
        let p = scene.track.points();
        let area: f64 = (0..p.len())
            .map(|i| {
                let (a, b) = (p[i], p[(i + 1) % p.len()]);
                a.x * b.y - b.x * a.y
            })
            .sum();
        turns.insert(area > 0.0);
    }
    assert!(dashed > 0 && solid > 0, "{dashed} dashed, {solid} solid");
    assert_eq!(turns.len(), 2, "tracks are driven both ways round");
}

#[test]
fn the_same_seed_gives_the_same_track_and_a_given_size_is_kept() {
    assert_eq!(
        generate(&options(9)).unwrap(),
        generate(&options(9)).unwrap()
    );
    for seed in 1..=20 {
        let o = GenerateOptions {
            size: Some((4.0, 3.5)),
            ..options(seed)
        };
        let world = generate(&o).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!((world.width, world.height), (4.0, 3.5));
    }
    assert_eq!("track".parse::<Style>(), Ok(Style::Track));
    assert_eq!(
        options(7).command(),
        "navdeck world generate --seed 7 --style track"
    );
}

#[test]
fn options_a_track_cannot_take_are_refused_by_name() {
    let refused = |o: GenerateOptions| match generate(&o) {
        Err(GenerateError::Option { option, .. }) => option,
        other => panic!("{other:?}"),
    };
    let colours = GenerateOptions {
        colours: Colours::Random,
        ..options(1)
    };
    assert_eq!(refused(colours), "colours");
    let bare = GenerateOptions {
        wall_markers: false,
        ..options(1)
    };
    assert_eq!(refused(bare), "no-wall-markers");
    let small = GenerateOptions {
        size: Some((3.0, 3.0)),
        ..options(1)
    };
    assert_eq!(refused(small), "size");
    let loops = GenerateOptions {
        loops: true,
        ..options(1)
    };
    assert_eq!(refused(loops), "loops");
}

/// A hand-made 6 m x 4 m world round a rounded rectangle driven clockwise (the right
/// side, where the posts stand, is inside), its control points scaled by `scale`, with
/// a light `side` metres left at the middle of the lower straight.
fn hand_made(points: &[[f64; 2]], scale: f64, side: f64) -> Result<World, String> {
    let points: Vec<[f64; 2]> = points
        .iter()
        .map(|p| [p[0] * scale, p[1] * scale])
        .collect();
    let bare = TrackSpec {
        points: points.clone(),
        ..toml::from_str::<TrackSpec>("points = []").unwrap()
    };
    let track = bare.build().map_err(|e| e.to_string())?.track;
    let light_at = track.project(Point2::new(0.0, -scale)).along;
    let start = track.project(Point2::new(0.0, scale));
    let (p, heading) = track.at(start.along);
    let text = format!(
        "name = \"hand-made\"\nsize = [6.0, 4.0]\nstart = [{}, {}, {}]\n\
         [[walls]]\npoints = [[-3.0, -2.0], [3.0, -2.0], [3.0, 2.0], [-3.0, 2.0]]\nclosed = true\n\
         [track]\npoints = {points:?}\n\
         [[track.lights]]\nat = {light_at}\nside = {side}\ncycle = {{ red = 5, green = 5, yellow = 2 }}\n",
        p.x,
        p.y,
        heading.to_degrees()
    );
    let world = World::from_toml(&text, Path::new("hand-made.toml")).map_err(|e| e.to_string())?;
    track_check::check(&world).map(|()| world)
}

const CLOCKWISE: [[f64; 2]; 10] = [
    [-1.6, 1.0],
    [0.0, 1.0],
    [1.6, 1.0],
    [2.3, 0.7],
    [2.3, -0.7],
    [1.6, -1.0],
    [0.0, -1.0],
    [-1.6, -1.0],
    [-2.3, -0.7],
    [-2.3, 0.7],
];

#[test]
fn the_checks_pass_a_sound_hand_made_track_and_refuse_bad_ones() {
    hand_made(&CLOCKWISE, 1.0, -0.35).unwrap();
    // Too tight: the same course at a third of its size.
    let e = hand_made(&CLOCKWISE, 0.35, -0.3).unwrap_err();
    assert!(e.contains("a bend of radius"), "{e}");
    // The post 2 m right of the lower straight stands on the upper one.
    let e = hand_made(&CLOCKWISE, 1.0, -2.0).unwrap_err();
    assert!(
        e.contains("post") && e.contains("from the lane's centre"),
        "{e}"
    );
    // Self-crossing: a figure of eight, each lobe round enough.
    let eight: Vec<[f64; 2]> = (0..16)
        .map(|k| {
            let a = k as f64 * std::f64::consts::TAU / 16.0;
            [2.4 * a.sin(), 1.6 * a.sin() * a.cos()]
        })
        .collect();
    let e = hand_made(&eight, 1.0, -0.35).unwrap_err();
    assert!(e.contains("comes back within"), "{e}");
    // Squeezed: a dumbbell whose waist leaves 0.72 m between its two sides.
    let dumbbell = [
        [-2.2, 1.2],
        [-1.3, 1.2],
        [0.0, 0.0],
        [1.3, 1.2],
        [2.2, 1.2],
        [2.7, 0.0],
        [2.2, -1.2],
        [1.3, -1.2],
        [0.0, 0.0],
        [-1.3, -1.2],
        [-2.2, -1.2],
        [-2.7, 0.0],
    ];
    let e = hand_made(&dumbbell, 0.9, -0.35).unwrap_err();
    assert!(e.contains("comes back within"), "{e}");
}

#[test]
fn a_start_off_the_lane_or_a_light_on_a_bend_is_refused() {
    let world = hand_made(&CLOCKWISE, 1.0, -0.35).unwrap();
    let mut off = world.clone();
    off.start.y -= 0.1;
    let e = track_check::check(&off).unwrap_err();
    assert!(e.contains("off the centreline"), "{e}");
    let mut backwards = world.clone();
    backwards.start.theta += std::f64::consts::PI;
    let e = track_check::check(&backwards).unwrap_err();
    assert!(e.contains("off the lane"), "{e}");
    let mut bent = world;
    let old_posts = bent.track.as_ref().unwrap().post_outlines();
    bent.walls.retain(|w| !old_posts.contains(w));
    let scene = bent.track.as_mut().unwrap();
    // The tightest point of the lane.
    let radii = track_check::local_radii(&scene.track, track_check::RADIUS_WINDOW);
    let tightest = (0..radii.len())
        .min_by(|&a, &b| radii[a].total_cmp(&radii[b]))
        .unwrap();
    let corner = tightest as f64 * scene.track.length() / radii.len() as f64;
    scene.lights[0] = crate::sim::track::TrafficLight::beside(
        &scene.track,
        corner,
        -0.35,
        scene.lights[0].cycle.clone(),
    );
    let new_posts = scene.post_outlines();
    bent.walls.extend(new_posts);
    let e = track_check::check(&bent).unwrap_err();
    assert!(e.contains("bends tighter"), "{e}");
}

#[test]
fn the_built_in_track_passes_the_checks_a_generated_one_does() {
    track_check::check(&World::default_track()).unwrap();
}

#[test]
fn every_generated_light_is_in_view_from_a_metre_before_its_line_to_the_line() {
    use crate::geometry::wrap_angle;
    for seed in 1..=SEEDS {
        let world = generate(&options(seed)).unwrap();
        let scene = world.track.as_ref().unwrap();
        for light in &scene.lights {
            for k in 0..=10 {
                let back = (light.along - 0.1 * f64::from(k)).rem_euclid(scene.track.length());
                let (p, heading) = scene.track.at(back);
                let post = light.position;
                let bearing = wrap_angle((post.y - p.y).atan2(post.x - p.x) - heading);
                assert!(
                    bearing.abs() <= track_check::APPROACH_BEARING + 1e-9,
                    "seed {seed}: {:.1} degrees {k}0 cm before the line",
                    bearing.to_degrees()
                );
            }
        }
    }
}
