//! Sensor health as a behaviour (priority 85; seed 000 §1.4 and §7.2.1's graceful
//! degradation): each frame says which sensors delivered usable data, each control step
//! declares those silent past their timeout lost, and a loss changes what the task may do:
//! - odometry lost: stop, every mode, until the wheels report again;
//! - lidar lost: the slow safety mode at once (`[safety.health]` `slow_linear`,
//!   `slow_angular`), the collision monitor on the planning map;
//! - camera lost: path following goes on where the lidar places the robot (MCL or lidar
//!   SLAM), and otherwise, and in the mission (which finds blocks by camera), the robot
//!   holds its position while mapping goes on; the keys still drive;
//! - arm lost: the mission picks up nothing new (`mission::step::Inputs::can_pick`),
//!   leaves a pick it is driving to for later and explores on; an arm already at work on
//!   a block (reaching, gripping, lifting, putting down) holds until it answers.
//!
//! Each loss and each recovery is logged once; the outages are kept for the JSON.

use super::{Behaviour, Proposal};
use crate::Pilot;
use crate::mode::Mode;
use crate::reckoning::Reckoning;
use navdeck_core::data::{Level, SensorFrame, WheelTravel};
use navdeck_core::geometry::Twist;
use navdeck_core::health::{Change, Sensor};

/// What sensor health does to the task this step.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Response {
    /// Nothing lost that matters here.
    Carry,
    /// The task is held: the robot stands, the mission's clock stops.
    Hold(String),
    /// The task's command is capped at (linear, angular).
    Slow(f64, f64),
}

/// Whether `frame` holds a usable camera frame: one arrived, and the pipeline could use it
/// (a dark or failed frame is no frame).
pub(crate) fn camera_usable(frame: &SensorFrame) -> bool {
    frame.sightings.is_some() && frame.camera.as_ref().is_none_or(|c| c.error.is_none())
}

impl Pilot {
    /// Notes the sensors that delivered usable data in `frame` at `t`; logs recoveries.
    pub(crate) fn note_sensor_health(&mut self, t: f64, frame: &SensorFrame) {
        let health = &mut self.behaviours.health;
        let arm_fitted = self.settings.arm.is_some();
        let delivered = [
            (Sensor::Odometry, frame.wheels.is_some()),
            (Sensor::Lidar, frame.scan.is_some()),
            (Sensor::Camera, camera_usable(frame)),
            (Sensor::Arm, arm_fitted && frame.arm.is_some()),
        ];
        let changes: Vec<Change> = (delivered.into_iter())
            .filter(|(_, yes)| *yes)
            .filter_map(|(sensor, _)| health.good(sensor, t))
            .collect();
        for change in changes {
            if let Change::Recovered { sensor, after } = change {
                let text = format!(
                    "{sensor} back after {after:.1} s: {}",
                    self.recovery(sensor)
                );
                self.log_at(t, Level::Success, text);
            }
        }
    }

    /// Declares the sensors silent past their timeout at `t` lost, each with what changes.
    pub(crate) fn check_sensor_health(&mut self, t: f64) {
        for change in self.behaviours.health.check(t) {
            if let Change::Lost { sensor, silent_for } = change {
                let reckoned = match sensor {
                    Sensor::Odometry => self.reckon_unmeasured(t),
                    _ => 0.0,
                };
                let what = match sensor {
                    Sensor::Odometry => "no wheel travel",
                    Sensor::Lidar => "no scan",
                    Sensor::Camera => "no usable camera frame",
                    Sensor::Arm => "no joint states",
                };
                let mut text = format!(
                    "{sensor} lost ({what} for {silent_for:.1} s): {}",
                    self.degradation(sensor)
                );
                if reckoned > 0.0 {
                    text +=
                        &format!(" ({reckoned:.2} m driven meanwhile, reckoned from the commands)");
                }
                self.log_at(t, Level::Warn, text);
            }
        }
    }

    /// Odometry was just found lost at `t`: the robot drove on blind since the wheels
    /// last reported. The commands sent meanwhile, through the base's acceleration limits,
    /// stand in for the travel they did not report (a motion model on the commanded
    /// velocity, as an EKF runs without wheel odometry), and go on standing in while the
    /// robot brakes, so that the estimate is not left behind; returns the metres reckoned.
    fn reckon_unmeasured(&mut self, t: f64) -> f64 {
        let commands = std::mem::take(&mut self.measuring.unmeasured);
        let Some(&(since, _)) = commands.front() else {
            return 0.0;
        };
        let robot = &self.settings.robot;
        let mut reckoning = Reckoning::new(since, self.measuring.measured);
        for &(at, twist) in &commands {
            reckoning.advance(at, robot);
            reckoning.command(twist);
        }
        reckoning.advance(t, robot);
        let travel = reckoning.travel;
        if travel != WheelTravel::default() {
            self.estimate_motion(travel);
        }
        self.measuring.reckoning = Some(reckoning);
        0.5 * (travel.left + travel.right).abs()
    }

    /// The link was lost: the sensors are judged afresh from the robot's next frame.
    pub(crate) fn restart_sensor_health(&mut self) {
        self.behaviours.health.restart();
    }

    /// What losing `sensor` changes, as the log says it.
    fn degradation(&self, sensor: Sensor) -> String {
        let c = self.behaviours.health.config();
        match sensor {
            Sensor::Odometry => "stopped until the wheels report again".into(),
            Sensor::Lidar => format!(
                "slow safety mode ({:.2} m/s, {:.2} rad/s), collision monitor on the map",
                c.slow_linear, c.slow_angular
            ),
            Sensor::Camera if self.lidar_places_robot() => {
                "localising on the lidar; the mission holds until it sees again".into()
            }
            Sensor::Camera => "autonomy holds position, mapping goes on".into(),
            Sensor::Arm => "picking up is skipped until it answers".into(),
        }
    }

    /// What recovering `sensor` restores, as the log says it.
    fn recovery(&self, sensor: Sensor) -> &'static str {
        match sensor {
            Sensor::Odometry | Sensor::Camera => "resuming",
            Sensor::Lidar => "full speed, collision monitor on the scan",
            Sensor::Arm => "picking up again",
        }
    }

    /// Whether the lidar places the robot without the camera: lidar SLAM, or MCL once it
    /// converged, with the lidar answering.
    pub(crate) fn lidar_places_robot(&self) -> bool {
        let lidar = !self.behaviours.health.is_lost(Sensor::Lidar);
        let placed =
            self.mcl().is_some_and(|m| m.status().converged) || self.lidar_slam().is_some();
        lidar && placed
    }

    /// Whether `sensor` is lost now.
    pub(crate) fn sensor_lost(&self, sensor: Sensor) -> bool {
        self.behaviours.health.is_lost(sensor)
    }

    /// What sensor health does to the mode's task now (nothing while switched off).
    pub(crate) fn health_response(&self) -> Response {
        if !self.behaviours.arbiter.is_on(Behaviour::SensorHealth) {
            return Response::Carry;
        }
        let lost = |s| self.sensor_lost(s);
        if lost(Sensor::Odometry) {
            return Response::Hold("odometry lost: stopped until the wheels report again".into());
        }
        let camera_holds = match self.mode {
            Mode::Exploration => true,
            Mode::PathFollowing => !self.lidar_places_robot(),
            _ => false,
        };
        if lost(Sensor::Camera) && camera_holds {
            return Response::Hold("camera lost: holding position, mapping goes on".into());
        }
        let reaching = (self.exploring.mission.as_ref()).is_some_and(|m| m.arm_engaged());
        if lost(Sensor::Arm) && self.mode == Mode::Exploration && reaching {
            return Response::Hold("arm lost: the block in its reach waits for it".into());
        }
        if lost(Sensor::Lidar) {
            let c = self.behaviours.health.config();
            return Response::Slow(c.slow_linear, c.slow_angular);
        }
        Response::Carry
    }

    /// Sensor health's proposal against the task's `twist` in the slow safety mode, when
    /// the cap changes it.
    pub(crate) fn slow_proposal(twist: Twist, linear: f64, angular: f64) -> Option<Proposal> {
        let capped = Twist::new(
            twist.linear.clamp(-linear, linear),
            twist.angular.clamp(-angular, angular),
        );
        (capped != twist).then(|| {
            let why = format!("lidar lost: slow safety mode, {linear:.2} m/s");
            Proposal::new(Behaviour::SensorHealth, capped, why)
        })
    }
}
