//! The generator's options: worlds without wall markers keep the layout of the same seed
//! with them, and loops give ways round that trees of rooms and corridors lack.

use super::rules::MIN_PASSAGE;
use super::{GenerateOptions, Style, check_reachable, generate};
use crate::geometry::Segment;
use crate::perception::markers::MarkerCategory;
use crate::sim::World;
use crate::sim::shapes::{rect_edges, segment_distance2};
use std::path::Path;

fn options(seed: u64, style: Style, size: (f64, f64)) -> GenerateOptions {
    GenerateOptions {
        seed,
        size: Some(size),
        style,
        ..GenerateOptions::default()
    }
}

/// Loads back from its own file as the same world and lets the robot reach everything.
fn assert_sound(world: &World) {
    let back = World::from_toml(&world.to_toml(), Path::new(&world.name))
        .unwrap_or_else(|e| panic!("{}: {e}", world.name));
    assert_eq!(&back, world, "{}: reads back", world.name);
    check_reachable(world).unwrap_or_else(|e| panic!("{}: {e}", world.name));
}

/// The walls that are not box outlines, grouped where they touch: each group's segments.
fn wall_groups(world: &World) -> Vec<Vec<Segment>> {
    let outlines: Vec<Segment> = (world.obstacles.iter())
        .flat_map(|o| rect_edges(o.pose, o.width, o.height))
        .collect();
    let plain: Vec<Segment> = (world.walls.iter())
        .filter(|s| {
            !outlines
                .iter()
                .any(|o| o.a.distance(s.a) < 1e-9 && o.b.distance(s.b) < 1e-9)
        })
        .copied()
        .collect();
    let mut group: Vec<usize> = (0..plain.len()).collect();
    // Join touching segments until nothing changes (a handful of walls).
    let mut changed = true;
    while changed {
        changed = false;
        for i in 0..plain.len() {
            for j in 0..plain.len() {
                let touch = segment_distance2(plain[i].a, plain[i].b, plain[j]) < 1e-12;
                if touch && group[j] > group[i] {
                    group[j] = group[i];
                    changed = true;
                }
            }
        }
    }
    let mut ids: Vec<usize> = group.clone();
    ids.sort_unstable();
    ids.dedup();
    ids.iter()
        .map(|&g| {
            (0..plain.len())
                .filter(|&k| group[k] == g)
                .map(|k| plain[k])
                .collect()
        })
        .collect()
}

/// Groups of walls the robot can go round: clear of the boundary's group by at least a
/// passage (the boundary is the first group: its walls are drawn first).
fn ways_round(world: &World) -> usize {
    let groups = wall_groups(world);
    let gap = |a: &[Segment], b: &[Segment]| {
        (a.iter())
            .flat_map(|s| b.iter().map(move |t| segment_distance2(s.a, s.b, *t)))
            .fold(f64::INFINITY, f64::min)
            .sqrt()
    };
    (1..groups.len())
        .filter(|&k| {
            (0..groups.len())
                .filter(|&j| j != k)
                .all(|j| gap(&groups[k], &groups[j]) >= MIN_PASSAGE - 1e-9)
        })
        .count()
}

#[test]
fn without_wall_markers_the_same_seed_gives_the_same_layout() {
    for style in Style::ALL {
        for seed in 1..=15 {
            let size = if style == Style::Boxes {
                (4.0, 4.0)
            } else {
                (7.0, 6.0)
            };
            let marked = generate(&options(seed, style, size)).unwrap();
            let bare_options = GenerateOptions {
                wall_markers: false,
                ..options(seed, style, size)
            };
            let bare = generate(&bare_options).unwrap_or_else(|e| panic!("{e}"));
            let name = &bare.name;
            assert_eq!(name, &format!("generated:{style}:{seed}:bare"));
            assert_ne!(name, &marked.name, "each keeps its own autosave");
            assert_eq!(bare.walls, marked.walls, "{name}");
            assert_eq!(bare.obstacles, marked.obstacles, "{name}");
            assert_eq!(bare.blocks, marked.blocks, "{name}");
            assert_eq!(bare.gates, marked.gates, "{name}");
            assert_eq!(bare.start, marked.start, "{name}");
            // Only the gates' markers are left; the blocks carry theirs.
            let kept: Vec<u32> = bare.markers.iter().map(|m| m.id).collect();
            let gates: Vec<u32> = marked.gates.iter().flat_map(|g| g.markers).collect();
            assert_eq!(kept.len(), gates.len(), "{name}: {kept:?}");
            assert!(kept.iter().all(|id| gates.contains(id)), "{name}: {kept:?}");
            assert!(
                marked
                    .markers
                    .iter()
                    .any(|m| MarkerCategory::of(m.id) == MarkerCategory::Boundary),
                "{name}: the marked world has wall markers"
            );
            assert_sound(&bare);
        }
    }
}

#[test]
fn rooms_and_corridors_are_trees_without_loops_and_have_ways_round_with_them() {
    for style in [Style::Rooms, Style::Corridors] {
        for (seed, size) in (1..=12).zip(
            [(6.0, 6.0), (9.0, 7.0), (12.0, 8.0), (12.0, 12.0)]
                .iter()
                .cycle(),
        ) {
            let tree = generate(&options(seed, style, *size)).unwrap();
            assert_eq!(ways_round(&tree), 0, "{}: a tree", tree.name);
            let looped = GenerateOptions {
                loops: true,
                wall_markers: false,
                ..options(seed, style, *size)
            };
            let world = generate(&looped).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(world.name, format!("generated:{style}:{seed}:loops:bare"));
            assert!(ways_round(&world) >= 1, "{}: no way round", world.name);
            assert_sound(&world);
        }
    }
}

#[test]
fn loops_are_refused_where_they_mean_nothing() {
    for style in [Style::Boxes, Style::Loop] {
        let o = GenerateOptions {
            loops: true,
            style,
            ..GenerateOptions::default()
        };
        let e = generate(&o).unwrap_err().to_string();
        assert!(e.contains("`loops`") && e.contains(style.label()), "{e}");
    }
}
