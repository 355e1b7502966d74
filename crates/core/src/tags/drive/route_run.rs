//! One task (or one target tag) driven through the tag graph (seed 003 §2.2-§2.6), the
//! part `navdeck route` and the console's route mode share: the waypoints still to
//! reach, the route planned through them by BFS, the driver on it, and the edges found
//! blocked. A blocked leg is driven back to its start and the rest planned again without
//! it (navdeck's: the seed has no recovery for a blocked edge).

use super::driver::{DriveEvent, DriveSetup, Phase, TagDriver};
use super::reset::TagSighting;
use crate::geometry::Pose2;
use crate::tags::file::{Direction, TagId, TagMap};
use crate::tags::graph::{Blocked, Leg, Route, RouteError};

/// A route being driven and what is left of its task.
#[derive(Clone, Debug)]
pub struct RouteRun {
    setup: DriveSetup,
    /// The tags the task must reach in order, the robot's start first.
    waypoints: Vec<TagId>,
    /// The index in `waypoints` of the next one to reach.
    next_waypoint: usize,
    blocked: Blocked,
    /// Edges found blocked, as (from, to) the way they were driven, in order.
    blocked_edges: Vec<(TagId, TagId)>,
    /// The tags of the route as first planned.
    planned: Vec<TagId>,
    route: Route,
    driver: TagDriver,
}

impl RouteRun {
    /// A run through `waypoints` (the first is where the robot starts) on `map`, the
    /// robot at map pose `start` with the odometry at `odom`.
    pub fn new(
        map: &TagMap,
        waypoints: Vec<TagId>,
        setup: DriveSetup,
        start: Pose2,
        odom: Pose2,
    ) -> Result<Self, RouteError> {
        let blocked = Blocked::new();
        let route = map.route(&waypoints, &blocked)?;
        let driver = TagDriver::new(map, &route, setup, start, odom);
        Ok(Self {
            setup,
            waypoints,
            next_waypoint: 1,
            blocked,
            blocked_edges: Vec::new(),
            planned: route.tags.clone(),
            route,
            driver,
        })
    }

    /// The waypoints of a task for a robot starting on `start`: `start`, then the task's
    /// waypoints without the copies of `start` it begins with.
    pub fn task_waypoints(start: TagId, task: &[TagId]) -> Vec<TagId> {
        let mut waypoints = vec![start];
        waypoints.extend(task.iter().copied().skip_while(|&w| w == start));
        waypoints
    }

    /// One control period of the driver; an arrival at the next waypoint counts it
    /// reached.
    pub fn step(
        &mut self,
        map: &TagMap,
        odom: Pose2,
        seen: &[TagSighting],
    ) -> ((f64, f64), Vec<DriveEvent>) {
        let (command, events) = self.driver.step(map, odom, seen);
        for e in &events {
            if let DriveEvent::Arrived { tag, .. } = e
                && self.waypoints.get(self.next_waypoint) == Some(tag)
            {
                self.next_waypoint += 1;
            }
        }
        (command, events)
    }

    /// The leg being driven (or searched along), if any.
    pub fn driving_leg(&self) -> Option<usize> {
        match self.driver.phase() {
            Phase::Drive { leg } | Phase::Search { leg } => Some(leg),
            _ => None,
        }
    }

    /// Marks leg `leg` blocked (both ways) and plans the rest again without it: back
    /// along the leg to its start, then on through the waypoints not yet reached. The
    /// robot's pose is the driver's estimate with the odometry at `odom`. The leg marked,
    /// or why there is no way round it.
    pub fn block(&mut self, map: &TagMap, leg: usize, odom: Pose2) -> Result<Leg, String> {
        let Some(&stopped) = self.route.legs.get(leg) else {
            return Err(format!("no leg {leg} in the route to mark blocked"));
        };
        self.blocked.insert((stopped.from, stopped.to));
        self.blocked.insert((stopped.to, stopped.from));
        self.blocked_edges.push((stopped.from, stopped.to));
        let mut rest = vec![stopped.from];
        rest.extend(&self.waypoints[self.next_waypoint.min(self.waypoints.len())..]);
        let route = route_back(map, stopped, &rest, &self.blocked).map_err(|why| {
            format!(
                "leg {}-{} is blocked and there is no way round it: {why}",
                stopped.from, stopped.to
            )
        })?;
        let est = self.driver.estimate(odom);
        self.driver = TagDriver::new(map, &route, self.setup, est, odom);
        self.route = route;
        Ok(stopped)
    }

    pub fn phase(&self) -> Phase {
        self.driver.phase()
    }

    /// The map pose the driver believes, with the odometry at `odom`.
    pub fn estimate(&self, odom: Pose2) -> Pose2 {
        self.driver.estimate(odom)
    }

    /// The route now being driven (planned again after a blocked leg).
    pub fn route(&self) -> &Route {
        &self.route
    }

    /// The tags of the route as first planned.
    pub fn planned(&self) -> &[TagId] {
        &self.planned
    }

    /// Edges found blocked, as (from, to), in order.
    pub fn blocked_edges(&self) -> &[(TagId, TagId)] {
        &self.blocked_edges
    }

    /// The next waypoint of the task to reach, if any is left.
    pub fn next_waypoint(&self) -> Option<TagId> {
        self.waypoints.get(self.next_waypoint).copied()
    }

    /// The waypoints not yet reached, in order.
    pub fn waypoints_left(&self) -> &[TagId] {
        &self.waypoints[self.next_waypoint.min(self.waypoints.len())..]
    }

    /// Leg `leg` of the route as a user reads it: "leg 3 (104 → 105)".
    pub fn leg_label(&self, leg: usize) -> String {
        match self.route.legs.get(leg) {
            Some(l) => format!("leg {} ({} → {})", leg + 1, l.from, l.to),
            None => match self.route.tags.last() {
                Some(tag) => format!("the end on tag {tag}"),
                None => "the route".into(),
            },
        }
    }
}

/// The leg from the middle of `stopped` back to its start, then on through `points`
/// (the first of them that start).
fn route_back(
    map: &TagMap,
    stopped: Leg,
    points: &[TagId],
    blocked: &Blocked,
) -> Result<Route, String> {
    let on = map.route(points, blocked).map_err(|e| e.to_string())?;
    let back = Leg {
        from: stopped.to,
        to: stopped.from,
        direction: match stopped.direction {
            Direction::Forward => Direction::Backward,
            Direction::Backward => Direction::Forward,
        },
        kind: stopped.kind,
    };
    let mut tags = vec![stopped.to];
    tags.extend(on.tags);
    let mut legs = vec![back];
    legs.extend(on.legs);
    Ok(Route { tags, legs })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 508 -> 1 -> 2 along the bottom and 508 -> 3 -> 4 -> 2 round the top, each way.
    const LOOP: &str = "
tags:
  508: {x: 0, y: 0, type: dock, zone: DOCK}
  1: {x: 1, y: 0, type: waypoint, zone: A}
  2: {x: 2, y: 0, type: shelf, zone: A}
  3: {x: 0, y: 1, type: pivot, zone: B}
  4: {x: 2, y: 1, type: pivot, zone: B}
edges:
  508:
    - {to: 1, direction: forward, type: straight}
    - {to: 3, direction: forward, type: pivot}
  1:
    - {to: 2, direction: forward, type: straight}
    - {to: 508, direction: backward, type: straight}
  2:
    - {to: 1, direction: backward, type: straight}
    - {to: 4, direction: forward, type: pivot}
  3:
    - {to: 4, direction: forward, type: pivot}
    - {to: 508, direction: backward, type: pivot}
  4:
    - {to: 2, direction: backward, type: pivot}
    - {to: 3, direction: backward, type: pivot}
tasks:
  fetch: {waypoints: [508, 2, 508]}
";

    #[test]
    fn a_blocked_leg_is_driven_back_and_the_rest_goes_round_it() {
        let map = TagMap::parse(LOOP).unwrap();
        let waypoints = RouteRun::task_waypoints(508, &map.tasks["fetch"]);
        assert_eq!(waypoints, [508, 2, 508]);
        let origin = Pose2::new(0.0, 0.0, 0.0);
        let mut run =
            RouteRun::new(&map, waypoints, DriveSetup::default(), origin, origin).unwrap();
        assert_eq!(run.planned(), [508, 1, 2, 1, 508]);
        assert_eq!(run.next_waypoint(), Some(2));
        // Held on 1 -> 2: back to 1, round by 508, 3 and 4 to 2, then home that way.
        let marked = run.block(&map, 1, origin).unwrap();
        assert_eq!((marked.from, marked.to), (1, 2));
        assert_eq!(run.route().tags, [2, 1, 508, 3, 4, 2, 4, 3, 508]);
        assert_eq!(run.route().legs[0].direction, Direction::Backward);
        assert_eq!(run.blocked_edges(), [(1, 2)]);
        assert_eq!(run.leg_label(0), "leg 1 (2 → 1)");
        // Held again on 4 -> 2: no way round is left, and the message names the leg.
        let why = run.block(&map, 4, origin).unwrap_err();
        assert!(
            why.starts_with("leg 4-2 is blocked and there is no way round it"),
            "{why}"
        );
    }
}
