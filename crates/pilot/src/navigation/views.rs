//! What the navigation shows the console and the reports: the route, the following,
//! arrival, and the cross-track error against the twin's truth.

use super::{FollowView, Route};
use crate::Pilot;
use crate::mode::Mode;
use navdeck_core::geometry::Point2;

impl Pilot {
    /// Cross-track error of the twin's true pose against the route, for the report.
    pub(super) fn sample_true_cross_track(&mut self) {
        let (Some(truth), Some(route)) = (self.estimating.truth, &self.nav.route) else {
            return;
        };
        let d = distance_to_polyline(&route.plan.trajectory.points, truth.position());
        self.nav.true_cross_track.add(d);
    }

    // ----- read-only views -----

    /// The planned path, if any.
    pub fn route(&self) -> Option<&Route> {
        self.nav.route.as_ref()
    }
    /// Progress along the path while following.
    pub fn following(&self) -> Option<FollowView> {
        self.nav.following
    }
    pub fn arrived(&self) -> bool {
        self.nav.arrived
    }
    pub fn follower(&self) -> &navdeck_core::control::follower::Follower {
        &self.follower
    }
    /// RMS cross-track error of the estimated pose since following started, replans
    /// included, metres.
    pub fn cross_track_rms(&self) -> Option<f64> {
        self.nav.cross_track.value()
    }
    /// RMS cross-track error of the twin's true pose over the last following, metres.
    pub fn true_cross_track_rms(&self) -> Option<f64> {
        self.nav.true_cross_track.value()
    }
    /// Paths the console planned again because the map changed under them.
    pub fn replans(&self) -> usize {
        self.nav.replans
    }

    /// Whether the robot is busy on its own (following a path, exploring, driving a route).
    pub fn is_busy(&self) -> bool {
        match self.mode {
            Mode::PathFollowing => self.follower.trajectory().is_some() && !self.nav.arrived,
            Mode::Exploration => self.mission().is_some_and(|m| !m.is_done()),
            Mode::Route => self.tag_route().driving(),
            _ => false,
        }
    }
}

/// Distance from `p` to the polyline through the trajectory's samples.
fn distance_to_polyline(
    points: &[navdeck_core::plan::trajectory::TrajectoryPoint],
    p: Point2,
) -> f64 {
    match points {
        [] => f64::INFINITY,
        [only] => only.position.distance(p),
        _ => points
            .windows(2)
            .map(|w| {
                navdeck_core::geometry::Segment::new(w[0].position, w[1].position).distance_to(p)
            })
            .fold(f64::INFINITY, f64::min),
    }
}
