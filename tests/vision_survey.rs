//! Survey (feature `vision`, run by hand with `--ignored --nocapture`): the rendered
//! camera's sightings over a grid of poses in the arena against the truth, per marker
//! category.
#![cfg(feature = "vision")]

use crate::vision_support;

use navdeck::geometry::Pose2;
use navdeck::perception::config::VisionConfig;
use navdeck::perception::markers::MarkerCategory;
use std::collections::BTreeMap;
use vision_support::{ArenaCamera, ArenaScene, level};

#[derive(Default, Debug)]
struct Stats {
    /// In the ideal sensor's view (fov 68.4, 0.1..3 m, 75 deg off face-on, clear line).
    ideal: usize,
    found: usize,
    wrong_id: usize,
    sum_dr: f64,
    sum_dr2: f64,
    sum_db: f64,
    sum_db2: f64,
    max_range_found: f64,
    min_range_found: f64,
    /// Sightings off by over 0.2 m or 5 degrees, and the shortest true range of one.
    gross: usize,
    gross_min_range: f64,
}

fn survey(cfg: &VisionConfig, label: &str) {
    let scene = ArenaScene::new();
    let mut camera = ArenaCamera::new(cfg, 5);
    let all = scene.markers();
    let occluders = scene.occluders();
    let mut stats: BTreeMap<&str, Stats> = BTreeMap::new();
    let mut poses = Vec::new();
    for i in 0..14 {
        for j in 0..14 {
            for k in 0..8 {
                let p = Pose2::new(
                    -1.75 + 0.27 * f64::from(i),
                    -1.75 + 0.27 * f64::from(j),
                    f64::from(k) * std::f64::consts::FRAC_PI_4 + 0.1,
                );
                poses.push(p);
            }
        }
    }
    for &pose in &poses {
        let frame = camera.frame(pose, all.iter().copied(), &occluders);
        let d = camera.det.detect(&frame, None).unwrap();
        for m in &all {
            let cat = MarkerCategory::of(m.id).label();
            let st = stats.entry(cat).or_insert(Stats {
                min_range_found: f64::INFINITY,
                ..Stats::default()
            });
            let (dx, dy) = (m.position.x - pose.x, m.position.y - pose.y);
            let range = dx.hypot(dy);
            let bearing = (dy.atan2(dx) - pose.theta + std::f64::consts::PI)
                .rem_euclid(std::f64::consts::TAU)
                - std::f64::consts::PI;
            let facing = (-(m.normal.cos() * dx + m.normal.sin() * dy) / range)
                .acos()
                .to_degrees();
            let clear = navdeck::sim::line_of_sight(pose.position(), m, &occluders);
            if clear
                && (0.1..=3.0).contains(&range)
                && bearing.abs() <= 34.2f64.to_radians()
                && facing <= 75.0
            {
                st.ideal += 1;
            }
            if let Some(s) = d.sightings.iter().find(|s| s.id == m.id) {
                st.found += 1;
                let dr = s.range - range;
                let db = (s.bearing - bearing).to_degrees();
                st.sum_dr += dr;
                st.sum_dr2 += dr * dr;
                st.sum_db += db;
                st.sum_db2 += db * db;
                st.max_range_found = st.max_range_found.max(range);
                st.min_range_found = st.min_range_found.min(range);
                if dr.abs() > 0.2 || db.abs() > 5.0 {
                    st.gross += 1;
                    st.gross_min_range = if st.gross == 1 {
                        range
                    } else {
                        st.gross_min_range.min(range)
                    };
                    eprintln!(
                        "gross: id {} true {range:.2} m {:.1} deg facing {facing:.0}: measured {:.2} m {:.1} deg, reproj {:.2}",
                        m.id,
                        bearing.to_degrees(),
                        s.range,
                        s.bearing.to_degrees(),
                        s.reprojection_px
                    );
                }
            }
        }
        for s in &d.sightings {
            if !all.iter().any(|m| m.id == s.id) {
                stats.entry("phantom").or_default().wrong_id += 1;
                eprintln!(
                    "phantom id {} at {:.2} m {:.1} deg from {pose:?}",
                    s.id,
                    s.range,
                    s.bearing.to_degrees()
                );
            }
        }
    }
    eprintln!("== {label}: {} poses", poses.len());
    for (cat, s) in &stats {
        let n = s.found.max(1) as f64;
        let (mr, mb) = (s.sum_dr / n, s.sum_db / n);
        eprintln!(
            "{cat:10} ideal {:5} found {:5} wrong {} | range err mean {:+.3} std {:.3} m | bearing err mean {:+.2} std {:.2} deg | found at {:.2}..{:.2} m | gross {} (nearest {:.2} m)",
            s.ideal,
            s.found,
            s.wrong_id,
            mr,
            (s.sum_dr2 / n - mr * mr).max(0.0).sqrt(),
            mb,
            (s.sum_db2 / n - mb * mb).max(0.0).sqrt(),
            s.min_range_found,
            s.max_range_found,
            s.gross,
            s.gross_min_range
        );
    }
}

#[test]
#[ignore]
fn survey_seed_mount() {
    survey(&VisionConfig::default(), "seed mount");
}

#[test]
#[ignore]
fn survey_twin_mount() {
    let mut v = VisionConfig::default();
    v.mount = v.render.mount.clone();
    v.detector.max_range = 3.0;
    survey(&v, "twin mount, 3 m");
}

#[test]
#[ignore]
fn survey_twin_mount_to_4_m() {
    let mut v = VisionConfig::default();
    v.mount = v.render.mount.clone();
    survey(&v, "twin mount, 4 m");
}

#[test]
#[ignore]
fn survey_level_mount() {
    survey(&level(), "level mount at 0.10 m");
}
