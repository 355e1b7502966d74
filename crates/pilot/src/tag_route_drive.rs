//! Route mode's stepping (seed 003 §2.3-§2.6): the run's command once a control period
//! as the tag route behaviour's proposal, what each step brought in the log, the pose
//! reset fed to the estimate, and a leg the collision monitor holds the robot on marked
//! blocked and routed round.

use crate::Pilot;
use crate::behaviours::{Behaviour, Proposal};
use crate::localize::ScanEstimator;
use crate::tag_route::BLOCKED_AFTER_S;
use nalgebra::{Matrix3, Vector3};
use navdeck_core::data::Level;
use navdeck_core::geometry::{Pose2, Twist};
use navdeck_core::tags::drive::{DriveEvent, Phase};

/// The spread of a pose reset from a tag: the ideal tag camera's 2 mm and 0.2°, widened
/// for the camera's mount (navdeck's figures).
const RESET_STD_M: f64 = 0.01;
const RESET_STD_RAD: f64 = 0.5 * std::f64::consts::PI / 180.0;

impl Pilot {
    /// The tag route behaviour's proposal at `t`: the run's command, stepped once a
    /// control period; standing still while there is no run.
    pub(crate) fn tag_route_proposal(&mut self, t: f64) -> Proposal {
        let (Some(map), true) = (self.tag_route.map.clone(), self.tag_route.run.is_some()) else {
            let why = match &self.tag_route.outcome {
                Some((_, text)) => text.clone(),
                None => "choose a task or a tag".into(),
            };
            return Proposal::new(Behaviour::TagRoute, Twist::ZERO, why);
        };
        let twist = match self.step_due(self.tag_route.last_step, t) {
            Err(twist) => twist,
            Ok(_) => {
                let seen = self.tag_route.fresh.take().unwrap_or_default();
                let odom = self.odometry.pose();
                let run = self.tag_route.run.as_mut().expect("checked above");
                let ((v, w), events) = run.step(&map, odom, &seen);
                self.log_route_events(t, &events);
                let twist = Twist::new(v, w);
                self.tag_route.last_step = Some((t, twist));
                twist
            }
        };
        let why = self.tag_route.phase_text();
        Proposal::new(Behaviour::TagRoute, twist, why)
    }

    fn log_route_events(&mut self, t: f64, events: &[DriveEvent]) {
        let goal = (self.tag_route.goal.as_ref()).map_or(String::new(), |g| g.label());
        for e in events {
            let Some(run) = self.tag_route.run.as_ref() else {
                return;
            };
            let legs = run.route().legs.len();
            let (level, text) = match e {
                DriveEvent::Arrived { leg, tag } => (
                    Level::Info,
                    format!("route: at tag {tag} (leg {} of {legs})", leg + 1),
                ),
                DriveEvent::Turned { .. } | DriveEvent::Aligned { .. } => continue,
                DriveEvent::Done => {
                    let last = run.route().tags.last().copied().unwrap_or(0);
                    (Level::Success, format!("route: {goal} done, on tag {last}"))
                }
                DriveEvent::Failed { leg, why } => (
                    Level::Error,
                    format!("route: {goal} failed on {}: {why}", run.leg_label(*leg)),
                ),
            };
            if matches!(e, DriveEvent::Done | DriveEvent::Failed { .. }) {
                self.tag_route.outcome = Some((level, text.clone()));
            }
            self.log_at(t, level, text);
        }
    }

    /// After the collision monitor weighed the route's `asked` twist at `t` (`held`: it
    /// stopped the robot): a leg held for `BLOCKED_AFTER_S` is marked blocked and the
    /// rest of the route planned round it.
    pub(crate) fn note_route_hold(&mut self, t: f64, asked: Twist, held: bool) {
        let stopped = held && asked.linear.abs() > 0.0;
        let leg = self.tag_route.run.as_ref().and_then(|r| r.driving_leg());
        let (Some(leg), true) = (leg, stopped) else {
            self.tag_route.held_since = None;
            return;
        };
        let since = *self.tag_route.held_since.get_or_insert(t);
        if t - since < BLOCKED_AFTER_S {
            return;
        }
        self.tag_route.held_since = None;
        let Some(map) = self.tag_route.map.clone() else {
            return;
        };
        let odom = self.odometry.pose();
        let Some(run) = self.tag_route.run.as_mut() else {
            return;
        };
        let label = run.leg_label(leg);
        match run.block(&map, leg, odom) {
            Ok(_) => {
                let tags: Vec<String> = run.route().tags.iter().map(|t| t.to_string()).collect();
                let text = format!(
                    "route: {label} blocked (the collision monitor held the robot {BLOCKED_AFTER_S:.0} s); back and round by {}",
                    tags.join(" → ")
                );
                self.tag_route.last_step = None;
                self.log_at(t, Level::Warn, text);
            }
            Err(why) => {
                // The run stops where it stands: its driver is left failed.
                self.tag_route.run = None;
                self.route_failed(why);
            }
        }
    }

    /// A pose from a tag placed in the estimate the console shows: the EKF's, and MCL's
    /// particles when it localises; lidar SLAM's mapping frame is left alone.
    pub(crate) fn reset_from_tag(&mut self, pose: Pose2) {
        let (sd, sa) = (RESET_STD_M, RESET_STD_RAD);
        match &mut self.scan_estimator {
            // Lidar SLAM maps in the frame the robot started in: moving the robot would
            // tear its map (slam_toolbox's mapping mode takes no pose either).
            ScanEstimator::Slam(_) => return,
            // MCL's particles gather round the tag's pose, as round an RViz pose estimate
            // but as tight as the tag's own error.
            ScanEstimator::Mcl(mcl) => mcl.init_at(pose, sd, sa),
            ScanEstimator::None => {}
        }
        let cov = Matrix3::from_diagonal(&Vector3::new(sd * sd, sd * sd, sa * sa));
        self.ekf.relocate(pose, &cov);
    }

    /// Whether route mode's run ended (done or failed), for the mode's status.
    pub fn tag_route_ended(&self) -> bool {
        (self.tag_route.run.as_ref())
            .is_some_and(|r| matches!(r.phase(), Phase::Done | Phase::Failed))
    }
}
