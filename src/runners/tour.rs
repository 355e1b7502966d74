//! `navdeck tour`: the robot drives itself round a twin world on simulated time, from one
//! random reachable goal to the next, and the estimate is scored against the truth: how
//! well it tracks, how soon a robot that does not know where it starts finds itself, and
//! how soon a kidnapped one does. No console: the pilot is driven directly, as the
//! mission runner does. While MCL has not yet localised, the robot wanders on its lidar
//! (ahead while the way is clear, else turning) instead of planning on a pose it has not
//! found.

use crate::config::Config;
use crate::data::Level;
use crate::geometry::{Point2, Pose2, Rms, wrap_angle};
use crate::link::RobotLink;
use crate::link::runtime::Runtime;
use crate::link::runtime::localising::LocalisingMove;
use crate::map::grid::OccupancyGrid;
use crate::pilot::localize::Localizer;
use crate::pilot::mode::Mode;
use crate::pilot::navigation::Target;
use crate::pilot::{Intent, LogLine, Pilot};
use crate::runners::mission::take_log;
use crate::slam::mcl::{KnownMap, Phase};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

/// Localised means within these of the truth (the global-localisation bar).
pub const LOCALISED_M: f64 = 0.10;
pub const LOCALISED_DEG: f64 = 5.0;
/// Goals keep this clear of obstacles beyond the footprint, metres.
const GOAL_CLEARANCE: f64 = 0.15;
/// Goals are at least this far from the robot, metres.
const GOAL_LEAST: f64 = 1.0;
/// A goal not reached in this long is given up, seconds.
const GOAL_PATIENCE: f64 = 90.0;

/// What a tour is asked to do.
#[derive(Clone, Debug)]
pub struct TourOptions {
    pub seed: u64,
    pub duration: f64,
    /// Carry the robot elsewhere at this time (a kidnapping), to that pose.
    pub kidnap: Option<(f64, Pose2)>,
    /// Goals to visit in turn instead of random ones.
    pub goals: Vec<Point2>,
    /// Start at a random reachable pose drawn from the seed instead of the world's start.
    pub random_start: bool,
}

/// One goal reached: where, when, and how far the true robot stopped from it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Arrival {
    pub goal: [f64; 2],
    pub time: f64,
    pub true_error: f64,
}

/// The outcome of one tour.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TourReport {
    pub world: String,
    pub seed: u64,
    pub estimator: String,
    pub sim_time: f64,
    pub distance: f64,
    #[serde(flatten)]
    pub errors: TourErrors,
    /// When the estimate first came within 10 cm and 5° with the filter converged.
    pub localised_at: Option<f64>,
    pub kidnapped_at: Option<f64>,
    /// Seconds from the kidnapping until localised again.
    pub recovered_after: Option<f64>,
    pub arrivals: Vec<Arrival>,
    pub goals_given_up: usize,
    pub worst_arrival_error: Option<f64>,
    pub collisions: Option<u32>,
    /// MCL at the end: particles, effective sample size, clusters.
    pub particles: Option<usize>,
    pub clusters: Option<usize>,
    /// What MCL said of itself against the truth.
    #[serde(flatten)]
    pub localisation: LocalisationScore,
    pub warnings: Vec<String>,
    pub wall_time_s: Option<f64>,
    pub realtime_factor: Option<f64>,
    /// The faults injected into the twin (`--fault`) and when each was in force; the
    /// sensors the pilot lost, and when each came back.
    #[serde(flatten)]
    pub faults: super::faults::FaultFigures,
}

/// The RMS errors of the estimate over the whole tour and of dead reckoning alone, and
/// the estimate's counted only once it first came within the localised bounds.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TourErrors {
    pub position_rmse: Option<f64>,
    pub heading_rmse_deg: Option<f64>,
    pub dr_position_rmse: Option<f64>,
    pub dr_heading_rmse_deg: Option<f64>,
    pub tracking_position_rmse: Option<f64>,
    pub tracking_heading_rmse_deg: Option<f64>,
}

/// MCL's own word against the truth: what it said at the end, how far off it was, and
/// whether it ever said "localised" while wrong.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct LocalisationScore {
    /// MCL's status at the end: "localised", "localising: 3 hypotheses", "lost: ...".
    pub localisation: Option<String>,
    /// The estimate's error at the end, metres and degrees.
    pub final_error_m: f64,
    pub final_error_deg: f64,
    /// Localised at the end, yet farther than `WRONG_M` or `WRONG_DEG` from the truth.
    pub confidently_wrong: bool,
    /// Seconds MCL said "localised" while that far from the truth.
    pub confidently_wrong_s: f64,
    /// When MCL first said it was lost (after a kidnapping).
    pub lost_at: Option<f64>,
}

/// Wrong means farther than these from the truth (the global-localisation bar).
pub const WRONG_M: f64 = 0.3;
pub const WRONG_DEG: f64 = 10.0;

/// Runs a tour on `link` (the twin) with `config`'s pilot, localised by `localizer` when given.
pub fn run(
    config: &Config,
    mut link: Box<dyn RobotLink>,
    localizer: Option<&Localizer>,
    options: &TourOptions,
) -> Result<TourReport, String> {
    let truth0 = link
        .ground_truth()
        .ok_or("a tour needs the twin: it scores the estimate against the truth")?;
    let world = truth0.world().clone();
    if let Some((_, pose)) = options.kidnap {
        crate::world_fit::pose_fits(
            &world,
            pose,
            config.robot.footprint_radius,
            "the kidnap pose",
        )
        .map_err(|why| format!("--kidnap: {why}"))?;
    }
    let raster = world.rasterize(0.05);
    let ground = localizer.map_or(&raster, |l| &l.grid);
    let start = truth0.pose();
    let goals = goal_cells(
        ground,
        start.position(),
        config.robot.footprint_radius + GOAL_CLEARANCE,
    )?;
    let mut rng = ChaCha8Rng::seed_from_u64(options.seed ^ 0x70_75_72);
    let mut localizer = localizer.cloned();
    if options.random_start {
        let p = goals[rng.random_range(0..goals.len())];
        let heading = rng.random_range(-std::f64::consts::PI..std::f64::consts::PI);
        let start = Pose2::new(p.x, p.y, heading);
        link.teleport(start);
        if let Some(l) = localizer.as_mut()
            && matches!(l.initial, crate::pilot::localize::InitialPose::At(_))
        {
            l.initial = crate::pilot::localize::InitialPose::At(start);
        }
    }
    let mut settings = config.pilot_settings();
    // The localising move drives its keys at race mode's speed (seed 001's high-speed
    // mode, 0.3 m/s by default) rather than the teleop's 0.15 m/s: at the slower speed a
    // 30 s search covers too little of a flat to reach where look-alike rooms differ.
    settings.teleop.linear_speed = settings.race.linear_speed.max(settings.teleop.linear_speed);
    let mut robot = Runtime::new(link, settings, 0.0);
    if let Some(l) = &localizer {
        l.apply(robot.pilot_mut())?;
    }
    let mut tour = Tour {
        rng,
        goals,
        next_listed: 0,
        goal: None,
        arrivals: Vec::new(),
        given_up: 0,
        log: Vec::new(),
        seek: LocalisingMove::default(),
    };
    let mut scores = Scores::default();
    take_log(&mut tour.log, robot.tick(0.0, Vec::new()));
    let period = config.robot.control_period;
    let mut t = 0.0;
    let mut kidnap = options.kidnap;
    while t < options.duration {
        t += period;
        if let Some((at, pose)) = kidnap
            && t >= at
        {
            robot.link_mut().teleport(pose);
            scores.kidnapped_at = Some(t);
            scores.localised_again = None;
            kidnap = None;
        }
        // What the tour asks rides in the control step at `t`.
        let intents = tour.steer(robot.pilot(), t, options);
        take_log(&mut tour.log, robot.tick(t, intents));
        let truth = robot.link().ground_truth().expect("checked above").pose();
        scores.add(t, truth, robot.pilot());
        tour.check_arrival(robot.pilot(), truth, t);
    }
    let truth = robot.link().ground_truth().expect("checked above");
    let mcl = robot.pilot().mcl().map(|m| m.status());
    let worst = tour
        .arrivals
        .iter()
        .map(|a| a.true_error)
        .fold(None, |m: Option<f64>, e| Some(m.map_or(e, |m| m.max(e))));
    Ok(TourReport {
        world: world.name.clone(),
        seed: options.seed,
        estimator: config.localization.estimator.label().to_string(),
        sim_time: t,
        distance: truth.distance_driven(),
        errors: TourErrors {
            position_rmse: scores.position.value(),
            heading_rmse_deg: scores.heading.value().map(f64::to_degrees),
            dr_position_rmse: scores.dr_position.value(),
            dr_heading_rmse_deg: scores.dr_heading.value().map(f64::to_degrees),
            tracking_position_rmse: scores.tracking_position.value(),
            tracking_heading_rmse_deg: scores.tracking_heading.value().map(f64::to_degrees),
        },
        localised_at: scores.localised_at,
        kidnapped_at: scores.kidnapped_at,
        recovered_after: (scores.kidnapped_at.zip(scores.localised_again)).map(|(k, l)| l - k),
        worst_arrival_error: worst,
        arrivals: tour.arrivals,
        goals_given_up: tour.given_up,
        collisions: Some(truth.collisions()),
        particles: mcl.map(|s| s.particles),
        clusters: mcl.map(|s| s.clusters),
        localisation: LocalisationScore {
            localisation: mcl.map(|s| s.summary()),
            ..scores.localisation
        },
        warnings: once_each(&tour.log),
        wall_time_s: None,
        realtime_factor: None,
        faults: super::faults::FaultFigures::of(robot.link(), robot.pilot()),
    })
}

/// The warnings in `log`, each text once at its first time, with how many times it came
/// when more than once (a goal off the map is refused at every control step).
fn once_each(log: &[LogLine]) -> Vec<String> {
    let mut seen: Vec<(&LogLine, usize)> = Vec::new();
    let mut at: std::collections::HashMap<&str, usize> = std::collections::HashMap::new();
    for line in log.iter().filter(|l| l.level >= Level::Warn) {
        match at.get(line.text.as_str()) {
            Some(&k) => seen[k].1 += 1,
            None => {
                at.insert(line.text.as_str(), seen.len());
                seen.push((line, 1));
            }
        }
    }
    seen.into_iter()
        .map(|(l, n)| match n {
            1 => format!("{:.1} s {}", l.time, l.text),
            n => format!("{:.1} s {} ({n} times)", l.time, l.text),
        })
        .collect()
}

/// Free cells a robot of clearance `clear` can stand on and reach from `start`.
fn goal_cells(grid: &OccupancyGrid, start: Point2, clear: f64) -> Result<Vec<Point2>, String> {
    let map = KnownMap::new(grid).map_err(|e| e.to_string())?;
    let open = |i: usize| grid.cells[i] == 0 && f64::from(map.distance_of(i)) >= clear;
    let first = (0..map.cells())
        .filter(|&i| open(i))
        .min_by(|&a, &b| {
            let (pa, pb) = (map.center(a), map.center(b));
            pa.distance(start).total_cmp(&pb.distance(start))
        })
        .ok_or("the world has no free cell clear enough for the robot to visit")?;
    let mut seen = vec![false; map.cells()];
    let mut stack = vec![first];
    seen[first] = true;
    let mut cells = Vec::new();
    while let Some(i) = stack.pop() {
        cells.push(map.center(i));
        let (x, y) = (i % grid.width, i / grid.width);
        let neighbours = [
            (x > 0).then(|| i - 1),
            (x + 1 < grid.width).then(|| i + 1),
            (y > 0).then(|| i - grid.width),
            (y + 1 < grid.height).then(|| i + grid.width),
        ];
        for n in neighbours.into_iter().flatten() {
            if !seen[n] && open(n) {
                seen[n] = true;
                stack.push(n);
            }
        }
    }
    Ok(cells)
}

/// The runner's state: what it logged, its goals, its arrivals.
struct Tour {
    rng: ChaCha8Rng,
    goals: Vec<Point2>,
    next_listed: usize,
    goal: Option<(Point2, f64)>,
    arrivals: Vec<Arrival>,
    given_up: usize,
    log: Vec<LogLine>,
    /// The move that tells MCL's hypotheses apart, while it has not localised.
    seek: LocalisingMove,
}

impl Tour {
    /// Decides what the robot does next: the localising move until localised, then goal
    /// after goal.
    fn steer(&mut self, pilot: &Pilot, t: f64, options: &TourOptions) -> Vec<Intent> {
        let mut asked = Vec::new();
        if LocalisingMove::wanted(pilot) {
            if self.goal.take().is_some() {
                asked.push(Intent::Mode(Mode::Manual));
            }
            asked.extend(self.seek.intents(pilot));
            return asked;
        }
        asked.extend(self.seek.stop());
        let stale = self
            .goal
            .is_some_and(|(_, since)| t - since > GOAL_PATIENCE);
        if stale {
            self.given_up += 1;
        }
        if self.goal.is_some() && pilot.mode() == Mode::PathFollowing && !stale {
            return asked;
        }
        if self.goal.is_some() && !pilot.arrived() {
            self.given_up += usize::from(!stale);
        }
        self.goal = None;
        if pilot.mode() != Mode::Manual {
            asked.push(Intent::Mode(Mode::Manual));
        }
        let here = pilot.estimated_pose().position();
        let goal = if options.goals.is_empty() {
            let far: Vec<Point2> = (self.goals.iter())
                .filter(|g| g.distance(here) >= GOAL_LEAST)
                .copied()
                .collect();
            let pool = if far.is_empty() { &self.goals } else { &far };
            pool[self.rng.random_range(0..pool.len())]
        } else {
            let g = options.goals[self.next_listed % options.goals.len()];
            self.next_listed += 1;
            g
        };
        asked.push(Intent::Goto(Target::Point(goal)));
        asked.push(Intent::Mode(Mode::PathFollowing));
        self.goal = Some((goal, t));
        asked
    }

    fn check_arrival(&mut self, pilot: &Pilot, truth: Pose2, t: f64) {
        if let Some((goal, _)) = self.goal
            && pilot.arrived()
            && pilot.commanded().is_zero()
            && self
                .arrivals
                .last()
                .is_none_or(|a| a.goal != [goal.x, goal.y])
        {
            self.arrivals.push(Arrival {
                goal: [goal.x, goal.y],
                time: t,
                true_error: truth.position().distance(goal),
            });
            self.goal = None;
        }
    }
}

/// Errors of the estimate and of dead reckoning against the truth.
#[derive(Default)]
struct Scores {
    position: Rms,
    heading: Rms,
    dr_position: Rms,
    dr_heading: Rms,
    tracking_position: Rms,
    tracking_heading: Rms,
    localised_at: Option<f64>,
    kidnapped_at: Option<f64>,
    localised_again: Option<f64>,
    localisation: LocalisationScore,
}

impl Scores {
    fn add(&mut self, t: f64, truth: Pose2, pilot: &Pilot) {
        let est = pilot.estimated_pose();
        let (dp, dh) = (
            truth.position().distance(est.position()),
            wrap_angle(truth.theta - est.theta),
        );
        self.position.add(dp);
        self.heading.add(dh);
        let dr = pilot.odometry_pose();
        self.dr_position
            .add(truth.position().distance(dr.position()));
        self.dr_heading.add(wrap_angle(truth.theta - dr.theta));
        let status = pilot.mcl().map(|m| m.status());
        let converged = status.is_none_or(|s| s.converged);
        let score = &mut self.localisation;
        score.final_error_m = dp;
        score.final_error_deg = dh.abs().to_degrees();
        let wrong = dp > WRONG_M || dh.abs().to_degrees() > WRONG_DEG;
        score.confidently_wrong = status.is_some() && converged && wrong;
        if score.confidently_wrong {
            score.confidently_wrong_s += pilot.settings().robot.control_period;
        }
        if score.lost_at.is_none() && status.is_some_and(|s| s.phase == Phase::Lost) {
            score.lost_at = Some(t);
        }
        let within = dp < LOCALISED_M && dh.abs().to_degrees() < LOCALISED_DEG && converged;
        if within && self.localised_at.is_none() {
            self.localised_at = Some(t);
        }
        if within && self.kidnapped_at.is_some() && self.localised_again.is_none() {
            self.localised_again = Some(t);
        }
        if self.localised_at.is_some() {
            self.tracking_position.add(dp);
            self.tracking_heading.add(dh);
        }
    }
}

/// The report for people.
pub fn human(r: &TourReport) -> String {
    let m = |v: Option<f64>, scale: f64, unit: &str| {
        v.map_or("-".into(), |v| format!("{:.3} {unit}", v * scale))
    };
    let mut s = format!(
        "tour of {} (seed {}), {}: {:.0} s simulated, {:.1} m driven, {} collisions\n",
        r.world,
        r.seed,
        r.estimator,
        r.sim_time,
        r.distance,
        r.collisions.unwrap_or(0)
    );
    s += &format!(
        "estimate RMSE {} / {}; dead reckoning {} / {}\n",
        m(r.errors.position_rmse, 1.0, "m"),
        m(r.errors.heading_rmse_deg, 1.0, "°"),
        m(r.errors.dr_position_rmse, 1.0, "m"),
        m(r.errors.dr_heading_rmse_deg, 1.0, "°"),
    );
    s += &format!(
        "localised at {}; kidnapped at {}, lost noticed at {}, recovered after {}\n",
        m(r.localised_at, 1.0, "s"),
        m(r.kidnapped_at, 1.0, "s"),
        m(r.localisation.lost_at, 1.0, "s"),
        m(r.recovered_after, 1.0, "s"),
    );
    s += &format!(
        "{} goals reached (worst true error {}), {} given up\n",
        r.arrivals.len(),
        m(r.worst_arrival_error, 1.0, "m"),
        r.goals_given_up
    );
    s += &r.faults.human();
    s
}
