//! Running navdeck without a terminal: play keys on simulated time, report the outcome.
//! The single way scripts and tests run a whole session.

use crate::app::log::Entry;
use crate::app::{App, KeyKind, LinkStatus};
use crate::geometry::Pose2;
use crate::keymap::Key;
use crate::runners::score::TruthScore;
use serde::Serialize;

/// Seconds the runner lets pass after the last key, beyond the deadman, for the robot to settle.
pub const SETTLE: f64 = 1.0;
/// Seconds the runner waits for a robot's link to answer before pressing keys.
pub const LINK_WAIT: f64 = 15.0;
/// Simulated seconds the runner waits for a path to be followed to its end.
pub const FOLLOW_TIMEOUT: f64 = 600.0;

/// What a headless run ended with.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Report {
    pub navdeck: &'static str,
    pub link: String,
    pub keys: usize,
    /// Simulated seconds the run covered.
    pub sim_time: f64,
    pub mode: String,
    /// Where the robot ended up and how far it went.
    #[serde(flatten)]
    pub travel: Travel,
    pub collisions: Option<u32>,
    /// Landmarks in the EKF's state at the end.
    pub landmarks: usize,
    /// Sightings beyond the EKF's chi-square gate.
    pub rejected_sightings: u64,
    /// The estimate's and the map's agreement with the twin's truth.
    #[serde(flatten)]
    pub score: TruthScore,
    pub gripper: Option<String>,
    #[serde(flatten)]
    pub following: Following,
    pub quit: bool,
    /// Warnings and errors the session logged, in order.
    pub warnings: Vec<String>,
    /// Wall-clock figures, filled in by the caller (the core reads no clock).
    pub wall_time_s: Option<f64>,
    pub realtime_factor: Option<f64>,
    /// What the session's recording holds (`--record`), filled in by the caller.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub recording: Option<crate::record::Summary>,
    /// A re-run of a recording (`navdeck replay --headless`): how it compares.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub replay: Option<crate::replay::Comparison>,
    /// The estimator and, with lidar SLAM, its pose graph's figures.
    #[serde(flatten)]
    pub estimator: super::slam_figures::EstimatorFigures,
    /// The faults injected into the twin (`--fault`, `:fault`) and when each was in force;
    /// the sensors the pilot lost, and when each came back.
    #[serde(flatten)]
    pub faults: super::faults::FaultFigures,
}

/// Where the robot ended up, truly and as estimated, and how far it went.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Travel {
    pub true_pose: Option<Pose2>,
    pub estimated_pose: Pose2,
    /// True path length in the twin; the wheels' figure where there is no twin.
    pub distance_driven: f64,
    pub odometry_distance: f64,
}

/// Path following: the controller, whether the goal was reached, and the RMS cross-track
/// error of the estimated pose and (in the twin) of the true pose, metres.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Following {
    pub controller: String,
    pub arrived: bool,
    pub path_length: Option<f64>,
    pub cross_track_rms: Option<f64>,
    pub true_cross_track_rms: Option<f64>,
    /// Route mode's run (seed 003) as the console shows it, when one was asked for:
    /// "done on tag 205", or the leg that failed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub route: Option<String>,
}

/// Presses `keys` through the active keymap at `rate` keys per simulated second, waits
/// (up to `FOLLOW_TIMEOUT`) while the robot follows a path, lets it come to rest, and reports.
pub fn run(app: &mut App, keys: &[Key], rate: f64) -> Report {
    run_keys(app, keys, rate, &mut |_| true, false)
}

/// As `run`, calling `pace(t)` before the session reaches time `t`: a real robot's link
/// passes a pacer that waits for the wall clock (the twin's runs need none), and the
/// session is brought up to date every control period between keys, as the console
/// does, so what the robot and other nodes send is taken in as it comes. The run ends
/// early, robot stopped, when `pace` returns false (a signal arrived).
pub fn run_paced(
    app: &mut App,
    keys: &[Key],
    rate: f64,
    pace: &mut dyn FnMut(f64) -> bool,
) -> Report {
    run_keys(app, keys, rate, pace, true)
}

fn run_keys(
    app: &mut App,
    keys: &[Key],
    rate: f64,
    pace: &mut dyn FnMut(f64) -> bool,
    every_period: bool,
) -> Report {
    let gap = 1.0 / rate;
    let start = app.now();
    let mut t = start;
    let mut step = |app: &mut App, t: f64| {
        let go_on = pace(t);
        if go_on {
            app.update(t);
        } else {
            app.shutdown("headless run interrupted");
        }
        go_on
    };
    // A real robot may take a moment to be discovered: keys wait for its first data.
    let period = app.config().robot.control_period;
    if app.link().ground_truth().is_none() {
        if !step(app, t) {
            return report(app, keys.len());
        }
        while app.pilot().link_status() != &LinkStatus::Ok && t < start + LINK_WAIT {
            t += period;
            if !step(app, t) {
                return report(app, keys.len());
            }
        }
    }
    for key in keys {
        if !step(app, t) {
            return report(app, keys.len());
        }
        app.handle_key(*key, KeyKind::Press, t);
        if app.should_quit() {
            break;
        }
        let next = t + gap;
        while every_period && t + period < next - 1e-9 {
            t += period;
            if !step(app, t) {
                return report(app, keys.len());
            }
        }
        t = next;
    }
    if !app.should_quit() {
        // The time after the last key is a control tick too.
        if !step(app, t) {
            return report(app, keys.len());
        }
        let give_up = t + FOLLOW_TIMEOUT;
        while app.pilot().is_busy() && t < give_up {
            t += period;
            if !step(app, t) {
                return report(app, keys.len());
            }
        }
        let end = t + app.config().teleop.deadman_timeout + SETTLE;
        while t < end {
            t = (t + period).min(end);
            if !step(app, t) {
                break;
            }
        }
    }
    report(app, keys.len())
}

/// The report of the session as it stands.
pub fn report(app: &App, keys: usize) -> Report {
    let twin = app.link().ground_truth();
    Report {
        navdeck: env!("CARGO_PKG_VERSION"),
        link: app.link().label(),
        keys,
        sim_time: app.now(),
        mode: app.pilot().mode().label().to_string(),
        travel: Travel {
            true_pose: app.true_pose(),
            estimated_pose: app.pilot().estimated_pose(),
            distance_driven: twin.map_or(app.pilot().odometry_distance(), |t| t.distance_driven()),
            odometry_distance: app.pilot().odometry_distance(),
        },
        collisions: twin.map(|t| t.collisions()),
        landmarks: app.pilot().slam().landmark_count(),
        rejected_sightings: app.pilot().slam().rejected(),
        score: TruthScore::of(app.pilot(), twin),
        gripper: app.pilot().gripper().map(|g| g.label().to_string()),
        following: Following {
            controller: app.pilot().follower().controller().name().to_string(),
            arrived: app.pilot().arrived(),
            path_length: app.pilot().route().map(|r| r.plan.length),
            cross_track_rms: app.pilot().cross_track_rms(),
            true_cross_track_rms: app.pilot().true_cross_track_rms(),
            route: (app.pilot().tag_route().goal()).map(|_| {
                let r = app.pilot().tag_route();
                r.outcome().map_or_else(|| r.phase_text(), str::to_string)
            }),
        },
        quit: app.should_quit(),
        // A robot node's line (its /rosout) names the node.
        warnings: app.log_book().problems().map(Entry::sourced_text).collect(),
        wall_time_s: None,
        realtime_factor: None,
        recording: None,
        replay: None,
        estimator: super::slam_figures::EstimatorFigures::of(app.pilot()),
        faults: super::faults::FaultFigures::of(app.link(), app.pilot()),
    }
}

/// A report as the few lines a person reads.
pub fn human(report: &Report) -> String {
    let mut out = format!(
        "navdeck headless on {}: {} keys, {:.1} s simulated\n",
        report.link, report.keys, report.sim_time
    );
    let p = report.travel.estimated_pose;
    out += &format!(
        "estimated pose  x {:.3} y {:.3} theta {:.1} deg\n",
        p.x,
        p.y,
        p.theta.to_degrees()
    );
    if let Some(t) = report.travel.true_pose {
        out += &format!(
            "true pose       x {:.3} y {:.3} theta {:.1} deg\n",
            t.x,
            t.y,
            t.theta.to_degrees()
        );
    }
    out += &format!("distance driven {:.3} m\n", report.travel.distance_driven);
    if let Some(c) = report.collisions {
        out += &format!("collisions      {c}\n");
    }
    out += &format!(
        "landmarks       {} ({} sightings rejected)\n",
        report.landmarks, report.rejected_sightings
    );
    if let (Some(line), Some(n)) = (report.score.line(), report.score.mean_nees) {
        out += &format!("error vs truth  {line}; mean NEES {n:.2}\n");
    }
    let following = &report.following;
    if let Some(length) = following.path_length {
        let arrived = if following.arrived {
            "arrived"
        } else {
            "not arrived"
        };
        out += &format!(
            "path            {length:.2} m, {arrived}, {} controller\n",
            following.controller
        );
    }
    if let Some(x) = following.cross_track_rms {
        out += &format!("cross-track     RMS {:.1} cm", x * 100.0);
        if let Some(t) = following.true_cross_track_rms {
            out += &format!(" (true pose {:.1} cm)", t * 100.0);
        }
        out += "\n";
    }
    out += &report.faults.human();
    if let Some(c) = &report.replay {
        out += &format!(
            "re-run          {} of {} control ticks' estimates identical to the recording; largest difference {:.4} m\n",
            c.identical, c.ticks, c.max_position_difference
        );
        if let (Some(a), Some(b), Some(ah), Some(bh)) = (
            c.recorded_position_rmse,
            c.rerun_position_rmse,
            c.recorded_heading_rmse_deg,
            c.rerun_heading_rmse_deg,
        ) {
            out += &format!(
                "error vs truth  recorded ({}) RMSE {a:.4} m, {ah:.2} deg; re-run ({}) RMSE {b:.4} m, {bh:.2} deg\n",
                c.recorded_estimator, c.rerun_estimator
            );
        }
    }
    if let Some(r) = &report.recording {
        let messages: u64 = r.topics.iter().map(|t| t.2).sum();
        out += &format!(
            "recorded        {} ({} bytes, {messages} messages)\n",
            r.path, r.bytes
        );
    }
    if let (Some(w), Some(f)) = (report.wall_time_s, report.realtime_factor) {
        out += &format!("wall time       {w:.3} s ({f:.0}x real time)\n");
    }
    // The last few warnings and errors: what went wrong is part of the report.
    let shown = report.warnings.len().saturating_sub(PROBLEMS_SHOWN);
    for w in &report.warnings[shown..] {
        out += &format!("problem         {w}\n");
    }
    out
}

/// Warnings and errors the human report lists, newest last.
const PROBLEMS_SHOWN: usize = 5;
