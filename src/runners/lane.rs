//! `navdeck lane`: the robot follows a track's lane in lane mode on simulated time, lap
//! after lap, through the twin's rendered colour camera and the OpenCV lane pipeline, and
//! the run is scored against the truth (seed 000 §6.1.1): laps, lateral error, time out
//! of lane, red lights run, barrier contacts, collisions, what held it and for how long,
//! and what the camera saw. No console: the pilot is driven directly, as the mission
//! runner does.

use crate::config::Config;
use crate::control::lane::Wait;
use crate::data::{BarrierState, LaneSighting, LightColour};
use crate::link::RobotLink;
use crate::link::runtime::{Event, Runtime};
use crate::pilot::mode::Mode;
use crate::pilot::{Intent, LogLine};
use crate::sim::track::{LaneFigures, LaneScore};
use serde::Serialize;

/// What a lane run is asked to do.
#[derive(Clone, Debug)]
pub struct LaneOptions {
    pub seed: u64,
    /// Laps to drive before the run ends.
    pub laps: f64,
    /// Simulated seconds after which the run ends unfinished.
    pub time_limit: f64,
    /// The lighting's name, for the report.
    pub lighting: String,
}

/// Frames the camera took and what the pipeline found in them.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Detections {
    pub frames: u32,
    /// Frames with a lane error (at least one line found).
    pub lane_found: u32,
    pub light_red: u32,
    pub light_yellow: u32,
    pub light_green: u32,
    pub barrier_down: u32,
    pub barrier_moving: u32,
    pub barrier_up: u32,
    /// Frames the pipeline could not use.
    pub failed: u32,
}

impl Detections {
    fn add(&mut self, s: &LaneSighting) {
        self.frames += 1;
        self.lane_found += u32::from(s.error_px.is_some());
        self.failed += u32::from(s.error.is_some());
        match s.light.map(|l| l.colour) {
            Some(LightColour::Red) => self.light_red += 1,
            Some(LightColour::Yellow) => self.light_yellow += 1,
            Some(LightColour::Green) => self.light_green += 1,
            None => {}
        }
        match s.barrier.map(|b| b.state) {
            Some(BarrierState::Down) => self.barrier_down += 1,
            Some(BarrierState::Moving) => self.barrier_moving += 1,
            Some(BarrierState::Up) => self.barrier_up += 1,
            None => {}
        }
    }
}

/// Times per frame of the lane pipeline, milliseconds.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct FrameTimes {
    pub frame_ms_mean: Option<f64>,
    pub frame_ms_std: Option<f64>,
    pub frame_ms_p95: Option<f64>,
    pub frame_ms_max: Option<f64>,
}

impl FrameTimes {
    fn of(ms: Vec<f64>) -> Self {
        let Some([mean, std, p95, max]) = spread(ms) else {
            return Self::default();
        };
        Self {
            frame_ms_mean: Some(mean),
            frame_ms_std: Some(std),
            frame_ms_p95: Some(p95),
            frame_ms_max: Some(max),
        }
    }
}

/// The mean, standard deviation, nearest-rank 95th percentile and maximum of `values`;
/// none when there are none.
pub fn spread(mut values: Vec<f64>) -> Option<[f64; 4]> {
    if values.is_empty() {
        return None;
    }
    values.sort_by(f64::total_cmp);
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / n;
    let p95 = values[((0.95 * n).ceil() as usize).clamp(1, values.len()) - 1];
    Some([mean, var.sqrt(), p95, values[values.len() - 1]])
}

/// What held the robot: how often and for how long.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Holds {
    pub light_stops: u32,
    pub barrier_stops: u32,
    pub lane_lost: u32,
    pub held_s: f64,
}

/// The outcome of one lane run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LaneReport {
    pub world: String,
    pub seed: u64,
    pub lighting: String,
    /// Whether the laps asked for were driven.
    pub completed: bool,
    pub sim_time: f64,
    pub distance: f64,
    #[serde(flatten)]
    pub figures: LaneFigures,
    pub barrier_hits: u32,
    pub collisions: u32,
    #[serde(flatten)]
    pub holds: Holds,
    pub detections: Detections,
    #[serde(flatten)]
    pub frame_times: FrameTimes,
    pub warnings: Vec<String>,
    pub wall_time_s: Option<f64>,
    pub realtime_factor: Option<f64>,
}

/// Runs lane mode on `link` (the twin with a lane camera) with `config`'s pilot.
pub fn run(
    config: &Config,
    link: Box<dyn RobotLink>,
    options: &LaneOptions,
) -> Result<LaneReport, String> {
    let truth0 = link
        .ground_truth()
        .ok_or("a lane run needs the twin: it scores the run against the truth")?;
    let world = truth0.world().clone();
    let scene = world
        .track
        .clone()
        .ok_or_else(|| format!("world {} has no [track] to follow", world.name))?;
    let mut score = LaneScore::new(&scene, truth0.pose(), config.robot.footprint_radius);
    let mut robot = Runtime::new(link, config.pilot_settings(), 0.0);
    let mut log: Vec<LogLine> = Vec::new();
    let mut detections = Detections::default();
    let mut holds = Holds::default();
    let mut times = Vec::new();
    let mut wait: Option<Wait> = None;
    let period = config.robot.control_period;
    let mut t = 0.0;
    let mut intents = vec![Intent::Mode(Mode::Lane)];
    loop {
        let stepped = robot.tick(t, std::mem::take(&mut intents));
        for e in &stepped.events {
            if let Event::Frame { frame, .. } = e
                && let Some(s) = &frame.lane
            {
                detections.add(s);
                times.extend(s.latency.map(|l| l * 1000.0));
            }
        }
        crate::runners::mission::take_log(&mut log, stepped);
        let pilot = robot.pilot();
        if t == 0.0 && pilot.mode() != Mode::Lane {
            let why = log
                .iter()
                .rev()
                .find(|l| l.level >= crate::data::Level::Warn);
            return Err(why.map_or("lane mode did not start".into(), |l| l.text.clone()));
        }
        let now_wait = pilot.lane().wait();
        if now_wait.is_some() {
            holds.held_s += period;
        }
        if now_wait != wait {
            match now_wait {
                Some(Wait::Light(_) | Wait::LookingForLight)
                    if !matches!(wait, Some(Wait::Light(_) | Wait::LookingForLight)) =>
                {
                    holds.light_stops += 1
                }
                Some(Wait::Barrier(_)) if !matches!(wait, Some(Wait::Barrier(_))) => {
                    holds.barrier_stops += 1
                }
                Some(Wait::LaneLost) => holds.lane_lost += 1,
                _ => {}
            }
            wait = now_wait;
        }
        let truth = robot.link().ground_truth().expect("checked above").pose();
        if t > 0.0 {
            score.observe(&scene, t, period, truth);
        }
        if score.laps(&scene) >= options.laps || t >= options.time_limit {
            break;
        }
        t += period;
    }
    // Stop the robot before reporting.
    robot.tick(t + period, vec![Intent::Mode(Mode::Manual)]);
    let truth = robot.link().ground_truth().expect("checked above");
    let figures = score.figures(&scene);
    Ok(LaneReport {
        world: world.name.clone(),
        seed: options.seed,
        lighting: options.lighting.clone(),
        completed: figures.laps >= options.laps,
        sim_time: t,
        distance: truth.distance_driven(),
        figures,
        barrier_hits: truth.barrier_hits(),
        collisions: truth.collisions(),
        holds,
        detections,
        frame_times: FrameTimes::of(times),
        warnings: (log.iter())
            .filter(|l| l.level >= crate::data::Level::Warn)
            .take(20)
            .map(|l| format!("{:.1} s {}", l.time, l.text))
            .collect(),
        wall_time_s: None,
        realtime_factor: None,
    })
}

/// A report for a person.
pub fn human(r: &LaneReport) -> String {
    let f = &r.figures;
    format!(
        "{} (seed {}, {}): {:.2} laps in {:.1} s{}; lateral RMS {:.1} mm, max {:.1} mm (bound {:.0} mm), {:.1} s out of lane; red lights run {}, barrier contacts {}, collisions {}; stops: {} at lights, {} at barriers, {} lane lost\n",
        r.world,
        r.seed,
        r.lighting,
        f.laps,
        r.sim_time,
        if r.completed { "" } else { " (unfinished)" },
        f.lateral_rms_m * 1000.0,
        f.lateral_max_m * 1000.0,
        f.in_lane_bound_m * 1000.0,
        f.out_of_lane_s,
        f.red_lights_run,
        r.barrier_hits,
        r.collisions,
        r.holds.light_stops,
        r.holds.barrier_stops,
        r.holds.lane_lost,
    )
}
