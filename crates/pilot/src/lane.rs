//! Lane mode (seed 000 §2-§3): lane following from the lane camera's sightings, with
//! traffic compliance holding the robot at red and yellow lights and at a barrier that is
//! down or moving. Both propose to the arbiter, traffic compliance (80) above lane
//! following (70), and the collision monitor (90) above both, so a box on the lane still
//! stops the robot.

use crate::Pilot;
use crate::behaviours::{Behaviour, Proposal};
use navdeck_core::control::lane::{LaneDriveConfig, LaneDriver, Wait};
use navdeck_core::data::{LaneSighting, Level};

/// The lane driver and what the lane camera last reported.
#[derive(Clone, Debug)]
pub struct Lane {
    driver: LaneDriver,
    /// The newest sighting, for the screen.
    last: Option<LaneSighting>,
    /// A sighting taken since the last control step.
    fresh: Option<LaneSighting>,
    /// What holds the robot now, if anything.
    wait: Option<Wait>,
    /// Why lane mode cannot run (no lane camera on this robot), if it cannot.
    unavailable: Option<String>,
}

impl Lane {
    pub fn new(cfg: LaneDriveConfig) -> Self {
        Self {
            driver: LaneDriver::new(cfg),
            last: None,
            fresh: None,
            wait: None,
            unavailable: None,
        }
    }

    /// The newest sighting.
    pub fn last(&self) -> Option<&LaneSighting> {
        self.last.as_ref()
    }

    /// What holds the robot in lane mode, if anything.
    pub fn wait(&self) -> Option<Wait> {
        self.wait
    }
}

impl Pilot {
    /// Lane mode's view: the newest sighting and the hold.
    pub fn lane(&self) -> &Lane {
        &self.lane
    }

    /// Says why lane mode cannot run on this robot (None: it can): set by whoever built
    /// the robot's sensors.
    pub fn set_lane_unavailable(&mut self, why: Option<String>) {
        self.lane.unavailable = why;
    }

    /// Why lane mode cannot start, if it cannot.
    pub(crate) fn lane_refusal(&self) -> Option<&str> {
        self.lane.unavailable.as_deref()
    }

    /// Takes in a lane sighting from the newest frame.
    pub(crate) fn sense_lane(&mut self, sighting: &LaneSighting) {
        self.lane.fresh = Some(sighting.clone());
        self.lane.last = Some(sighting.clone());
    }

    /// Lane mode entered at `t`: a fresh start, nothing held.
    pub(crate) fn enter_lane(&mut self, t: f64) {
        self.lane.driver.reset(t);
        self.lane.wait = None;
        self.lane.fresh = None;
    }

    /// Lane mode's proposals at `t`: lane following's twist, and traffic compliance's
    /// hold when a light or a barrier holds the robot.
    pub(crate) fn lane_proposals(&mut self, t: f64) -> (Proposal, Option<Proposal>) {
        let fresh = self.lane.fresh.take();
        let speed = self.measuring.measured.linear;
        let step = self.lane.driver.step(t, fresh.as_ref(), speed);
        if step.wait != self.lane.wait {
            match step.wait {
                Some(w) => self.log_at(t, Level::Info, w.text()),
                None => self.log_at(t, Level::Info, "lane: driving on"),
            }
            self.lane.wait = step.wait;
        }
        let reason = match step.wait {
            Some(Wait::LaneLost) => Wait::LaneLost.text(),
            _ => "following the lane".into(),
        };
        let follow = Proposal::new(Behaviour::LaneFollowing, step.twist, reason);
        let hold = match step.wait {
            Some(w @ (Wait::Light(_) | Wait::LookingForLight | Wait::Barrier(_))) => {
                Some(Proposal::new(
                    Behaviour::TrafficCompliance,
                    navdeck_core::geometry::Twist::ZERO,
                    w.text(),
                ))
            }
            _ => None,
        };
        (follow, hold)
    }
}
