//! The pilot's one entry point: `Pilot::step(Input, &mut dyn Robot) -> Output`. One step
//! applies what the user asked, polls the robot when the step needs it, folds in what it
//! reported, decides the command and sends it: one key, one step.

use crate::{Output, Pilot};
use navdeck_core::data::{Command, SensorFrame};
use navdeck_core::geometry::Pose2;

/// The robot as one step sees it: the runner's link behind three calls. The pilot never
/// holds it between steps, so it reads no clock and opens nothing itself.
pub trait Robot {
    /// What the robot reported up to session time `t`, or why it could not be polled.
    fn poll(&mut self, t: f64) -> Result<SensorFrame, String>;
    /// The robot's true pose when a simulator knows it: used to score, never to decide.
    fn truth(&self) -> Option<Pose2>;
    /// Sends `command`, or says why it could not.
    fn send(&mut self, command: &Command) -> Result<(), String>;
}

/// What the step should do besides applying the intent.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Due {
    /// Only the intent: nothing is polled or sent, whatever it changed.
    Apply,
    /// Nothing more, unless the intent changed the robot's motion: then the robot is
    /// polled and commanded at once, as with `Command`.
    IfActing,
    /// Poll the robot and fold in what it reported; no command.
    Sense,
    /// A command now (a key acted between control periods).
    Command,
    /// A command and the once-per-period upkeep (measured twist, footprint, accuracy).
    Tick,
}

/// One step's input.
#[derive(Debug)]
pub struct Input {
    /// Session time, seconds.
    pub t: f64,
    pub intent: Option<crate::Intent>,
    pub due: Due,
}

impl Input {
    /// An intent at `t`: the robot is polled and commanded when it changed the motion.
    pub fn intent(t: f64, intent: crate::Intent) -> Self {
        let intent = Some(intent);
        let due = Due::IfActing;
        Self { t, intent, due }
    }

    /// An intent at `t` applied alone: its command follows with the next step.
    pub fn apply(t: f64, intent: crate::Intent) -> Self {
        let intent = Some(intent);
        let due = Due::Apply;
        Self { t, intent, due }
    }

    /// A step at `t` with no intent, doing what `due` says.
    pub fn due(t: f64, due: Due) -> Self {
        Self {
            t,
            intent: None,
            due,
        }
    }
}

impl Pilot {
    /// The one entry point: applies the intent, polls `robot` and folds in what it
    /// reported, decides the command when one is due and sends it. A failed poll or send
    /// puts the pilot's link in doubt.
    pub fn step(&mut self, input: Input, robot: &mut dyn Robot) -> Output {
        let t = input.t;
        self.now = self.now.max(t);
        self.estimating.truth = robot.truth();
        let acts = input.intent.is_some_and(|intent| self.apply(intent));
        let due = match input.due {
            Due::IfActing if acts => Due::Command,
            due => due,
        };
        let mut out = Output::default();
        if !matches!(due, Due::IfActing | Due::Apply) {
            let polled = robot.poll(t);
            self.estimating.truth = robot.truth();
            match &polled {
                Ok(frame) => self.sense(t, frame),
                Err(reason) => self.lose_link(t, reason.clone()),
            }
            match polled {
                Ok(frame) => out.frame = Some(frame),
                Err(reason) => out.failure = Some(reason),
            }
            if due != Due::Sense {
                let command = self.act(t);
                if due == Due::Tick {
                    self.upkeep_tick();
                }
                if let Err(e) = robot.send(&command) {
                    self.lose_link(t, format!("command not sent: {e}"));
                }
                out.command = Some(command);
            }
        }
        out.log = std::mem::take(&mut self.log);
        out
    }

    /// The once-per-period upkeep: measured twist, footprint, accuracy, race's check.
    fn upkeep_tick(&mut self) {
        self.measure();
        self.map_footprint();
        self.sample_accuracy();
        self.check_race_uncertainty();
    }
}
