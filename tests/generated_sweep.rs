//! The mission on generated worlds that vary as users' do: size, block count, colours
//! (random, all one, alternating), wall-marker spacing and doorway width drawn from each
//! seed. The sweeps are `--ignored`:
//!
//! `cargo test --release --all-features --test suite -- --ignored generated_sweep:: --nocapture`
//!
//! (`NAVDECK_SWEEP=A..B` picks the seeds, 1..100 unless set.)

use crate::common;

use rand::{Rng, SeedableRng};
use serde_json::Value;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};

/// One world's options, drawn from `style` and `seed`: boxes worlds 4-6 × 4-5 m, rooms
/// and corridors 6-12 × 5-8 m, 3-8 blocks, markers every 0.5-1.2 m, doorways 0.7-1.0 m.
fn drawn(style: &str, seed: u64) -> Vec<String> {
    let salt = style
        .bytes()
        .fold(0u64, |h, b| h.wrapping_mul(31).wrapping_add(u64::from(b)));
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed ^ salt.rotate_left(32));
    let (w, h) = match style {
        "boxes" => (rng.random_range(4.0..6.0), rng.random_range(4.0..5.0)),
        _ => (rng.random_range(6.0..12.0), rng.random_range(5.0..8.0)),
    };
    let colours = ["random", "one", "alternating"][rng.random_range(0..3)];
    let mut args = vec![
        format!("--size={w:.1},{h:.1}"),
        format!("--blocks={}", rng.random_range(3..=8)),
        format!("--colours={colours}"),
        format!("--marker-spacing={:.2}", rng.random_range(0.5..1.2)),
        format!(
            "--time-limit={}",
            if style == "corridors" { 3000 } else { 1500 }
        ),
    ];
    let doorway = rng.random_range(0.7..1.0);
    if style != "boxes" {
        args.push(format!("--doorway={doorway:.2}"));
    }
    args
}

fn run(style: &str, seed: u64) -> Value {
    let args = drawn(style, seed);
    let extra: Vec<&str> = args.iter().map(String::as_str).collect();
    common::generated_mission(style, &seed.to_string(), &extra)
}

/// Runs `style` on every seed of `NAVDECK_SWEEP` (1..100) two at a time and prints each
/// run that fell short and the totals; asserts what must hold in every run: the count
/// the mission gives is the twin's, and nothing was touched.
fn sweep(style: &str) {
    let range = std::env::var("NAVDECK_SWEEP").unwrap_or_else(|_| "1..100".into());
    let (a, b) = range.split_once("..").expect("NAVDECK_SWEEP is A..B");
    let (a, b): (u64, u64) = (a.parse().unwrap(), b.parse().unwrap());
    let next = AtomicU64::new(a);
    let runs = Mutex::new(Vec::new());
    std::thread::scope(|s| {
        for _ in 0..2 {
            s.spawn(|| {
                loop {
                    let seed = next.fetch_add(1, Ordering::Relaxed);
                    if seed > b {
                        break;
                    }
                    let r = run(style, seed);
                    runs.lock().unwrap().push((seed, r));
                }
            });
        }
    });
    let mut runs = runs.into_inner().unwrap();
    runs.sort_by_key(|(seed, _)| *seed);
    let (mut all, mut blocks, mut placed, mut times) = (0, 0, 0, Vec::new());
    // A run counts as all delivered only with every block at its gate, the mission's
    // count the twin's, and nothing touched; each other run is printed.
    let (mut dishonest, mut touched) = (0, 0);
    for (seed, r) in &runs {
        let total = r["total"].as_u64().unwrap();
        let truly = r["true_delivered"].as_u64().unwrap();
        (blocks, placed) = (blocks + total, placed + truly);
        dishonest += usize::from(r["delivered"] != r["true_delivered"]);
        touched += r["collisions"].as_u64().unwrap();
        let clean = r["collisions"] == 0 && r["delivered"] == r["true_delivered"];
        if r["outcome"] == "delivered all" && truly == total && clean {
            all += 1;
            times.push(r["sim_time"].as_f64().unwrap());
        } else {
            println!(
                "{style} seed {seed} ({}): {}, {truly}/{total} at their gates, mission's count {}, \
                 {} collisions",
                drawn(style, *seed).join(" "),
                r["cause"],
                r["delivered"],
                r["collisions"]
            );
        }
    }
    times.sort_by(f64::total_cmp);
    println!(
        "{style}: every block delivered in {all}/{} runs; blocks {placed}/{blocks}; \
         count unlike the twin's in {dishonest}; collisions {touched}; median {:.0} s",
        runs.len(),
        times.get(times.len() / 2).copied().unwrap_or(f64::NAN)
    );
    assert_eq!(
        dishonest, 0,
        "the mission's count is the twin's in every run"
    );
    assert_eq!(touched, 0, "no run touches anything");
}

#[test]
#[ignore = "100 worlds, minutes even in release"]
fn boxes() {
    sweep("boxes");
}

#[test]
#[ignore = "100 worlds, minutes even in release"]
fn rooms() {
    sweep("rooms");
}

#[test]
#[ignore = "100 worlds with up to 3000 s each, the longest sweep"]
fn corridors() {
    sweep("corridors");
}
