//! When a robot of a fleet waits instead of choosing: what is left to explore lies in
//! ground another robot claims (it is looking there now), or nothing is left but
//! another robot stands at the edge of the space this one can reach (it may be what
//! hides the rest, as when a robot starts boxed in by the others). Waiting is turning
//! where it stands, a quarter turn at a time, and choosing again. A robot with nothing
//! left goes back to where it started before it ends, so that it does not end standing
//! in the way of the others (beside the block another robot is carrying off, say).

use super::config::{TARGET_TOO_CLOSE, WAIT_TURN};
use super::drive::Turn;
use super::leg::Leg;
use super::machine::Mission;
use super::phase::{Phase, Target};
use super::step::{Inputs, Level};
use crate::geometry::Point2;

/// A robot whose centre is this near a cell the mission can reach stands at the edge of
/// its space, metres: the planning map's ring round an obstacle (0.30 m, README "rings")
/// and half a robot (0.105 m, a TurtleBot3's half-width), rounded up.
const AT_THE_EDGE: f64 = 0.45;
/// The longest a mission waits for other robots to move off the edge of its space
/// before calling exploration complete, seconds (navdeck's).
pub(super) const BOXED_WAIT: f64 = 60.0;

impl Mission {
    /// Waits, turning, when every target left was left out because another robot claims
    /// its ground. Returns whether it waits.
    pub(super) fn wait_for_claims(
        &mut self,
        inputs: &Inputs,
        log: &mut Vec<(Level, String)>,
    ) -> bool {
        if !self.shared.claimed_out {
            return false;
        }
        if !self.shared.waiting {
            log.push((
                Level::Info,
                "What is left to explore is another robot's - waiting, turning".into(),
            ));
        }
        self.shared.waiting = true;
        self.wait_turn(inputs);
        true
    }

    /// Waits, turning, when nothing is left to do before it reached any goal but another
    /// robot of the fleet stands at the edge of the space this one can reach (`reach`,
    /// from `targets::reachable`), for `BOXED_WAIT` at most. Returns whether it waits.
    pub(super) fn wait_for_the_boxed_in(
        &mut self,
        inputs: &Inputs,
        reach: &[bool],
        log: &mut Vec<(Level, String)>,
    ) -> bool {
        if !self.explored.visited_goals.is_empty() {
            return false;
        }
        let Some(peer) = self.peer_at_the_edge(inputs, reach) else {
            return false;
        };
        let since = *self.shared.boxed_since.get_or_insert(inputs.t);
        if inputs.t - since >= BOXED_WAIT {
            log.push((
                Level::Warn,
                format!(
                    "Another robot still stands at the edge of the space within reach after {BOXED_WAIT:.0} s"
                ),
            ));
            return false;
        }
        if since == inputs.t {
            log.push((
                Level::Info,
                format!(
                    "Nothing left within reach, and another robot stands at its edge ({:.2}, {:.2}) - waiting for it to move, turning",
                    peer.x, peer.y
                ),
            ));
        }
        self.wait_turn(inputs);
        true
    }

    /// Another robot of the fleet within `AT_THE_EDGE` of a cell the mission can reach.
    fn peer_at_the_edge(&self, inputs: &Inputs, reach: &[bool]) -> Option<Point2> {
        let map = inputs.map;
        if reach.len() != map.width * map.height || map.resolution <= 0.0 {
            return None;
        }
        let k = (AT_THE_EDGE / map.resolution).ceil() as i64;
        let near = |p: Point2| {
            let Some((cx, cy)) = map.cell_of(p) else {
                return false;
            };
            (-k..=k).any(|dy| {
                (-k..=k).any(|dx| {
                    let (x, y) = (cx as i64 + dx, cy as i64 + dy);
                    let inside = x >= 0 && y >= 0 && x < map.width as i64 && y < map.height as i64;
                    inside
                        && reach[map.index(x as usize, y as usize)]
                        && map.center_of(x as usize, y as usize).distance(p) <= AT_THE_EDGE
                })
            })
        };
        self.shared.fleet.peers.iter().copied().find(|p| near(*p))
    }

    /// In a fleet, with nothing left: back to where the mission started, once. Returns
    /// whether it goes.
    pub(super) fn go_home(&mut self, inputs: &Inputs, log: &mut Vec<(Level, String)>) -> bool {
        let Some(home) = self.shared.home else {
            return false;
        };
        let away = home.distance(inputs.pose.position()) >= TARGET_TOO_CLOSE;
        if self.shared.fleet.peers.is_empty() || self.shared.home_reached || !away {
            return false;
        }
        log.push((
            Level::Info,
            "Nothing left to do here - going back to where this robot started, out of the others' way".into(),
        ));
        self.phase = Phase::Explore {
            leg: Leg::replaceable(home, "where it started".into()),
            target: Target::Home,
        };
        true
    }

    fn wait_turn(&mut self, inputs: &Inputs) {
        self.phase = Phase::Scan {
            turn: Turn::new(inputs.pose, inputs.t, WAIT_TURN, self.config.scan_speed),
            initial: false,
        };
    }
}
