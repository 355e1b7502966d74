//! Running one simulated run per seed on every core (`--sweep A..B`), and pacing a run
//! on real robots by the wall clock.

use navdeck::tui::signals::Signals;
use std::time::Instant;

/// `one(run)` for every run (a seed, or a seed and a lighting), on as many threads as
/// there are cores (no more than runs), returned in the runs' order.
pub(crate) fn on_all_cores<I: Copy + Sync, T: Send>(
    runs: &[I],
    one: impl Fn(I) -> T + Sync,
) -> Vec<T> {
    let next = std::sync::atomic::AtomicUsize::new(0);
    let workers = std::thread::available_parallelism().map_or(2, |n| n.get());
    let results = std::sync::Mutex::new(Vec::new());
    std::thread::scope(|scope| {
        for _ in 0..workers.min(runs.len()) {
            scope.spawn(|| {
                loop {
                    let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    let Some(&run) = runs.get(k) else { break };
                    let report = one(run);
                    results
                        .lock()
                        .expect("no worker panicked")
                        .push((k, report));
                }
            });
        }
    });
    let mut results = results.into_inner().expect("no worker panicked");
    results.sort_by_key(|(k, _)| *k);
    results.into_iter().map(|(_, r)| r).collect()
}

/// A pacer for a headless run on real robots: it waits until session time `t` is due on
/// the wall clock counted from `started`, and says false once a signal has arrived.
pub(crate) fn wall_pacer(started: Instant, signals: &Signals) -> impl FnMut(f64) -> bool + '_ {
    move |t: f64| {
        let ahead = t - started.elapsed().as_secs_f64();
        if ahead > 0.0 {
            std::thread::sleep(std::time::Duration::from_secs_f64(ahead));
        }
        signals.pending().is_none()
    }
}
