//! Routes through the tag graph: BFS between tags (seed 003 §1.2.3 `find_path`, §2.2
//! mode 3), a task's waypoints joined leg by leg, and blocked edges left out when a
//! route is planned again.

use super::file::{Direction, EdgeKind, TagId, TagMap};
use std::collections::BTreeSet;

/// Edges a route may not use, as (from, to).
pub type Blocked = BTreeSet<(TagId, TagId)>;

/// One edge of a route.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Leg {
    pub from: TagId,
    pub to: TagId,
    pub direction: Direction,
    pub kind: EdgeKind,
}

/// The tags a route visits, first to last, and the legs between them.
#[derive(Clone, Debug, PartialEq)]
pub struct Route {
    pub tags: Vec<TagId>,
    pub legs: Vec<Leg>,
}

/// Why no route was found.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum RouteError {
    #[error("no tag {0} in the map")]
    UnknownTag(TagId),
    /// No way along the graph's edges (less the blocked ones) from one tag to the next.
    #[error("no way along the edges from tag {from} to tag {to}")]
    NoPath { from: TagId, to: TagId },
}

impl TagMap {
    /// The fewest-edge way from `start` to `goal` (BFS, edges tried in the file's order),
    /// leaving out `blocked`.
    pub fn find_path(
        &self,
        start: TagId,
        goal: TagId,
        blocked: &Blocked,
    ) -> Result<Vec<TagId>, RouteError> {
        for id in [start, goal] {
            if !self.tags.contains_key(&id) {
                return Err(RouteError::UnknownTag(id));
            }
        }
        let next = |&at: &TagId| -> Vec<TagId> {
            (self.edges.get(&at).into_iter().flatten())
                .filter(|e| !blocked.contains(&(at, e.to)))
                .map(|e| e.to)
                .collect()
        };
        pathfinding::directed::bfs::bfs(&start, next, |&at| at == goal).ok_or(RouteError::NoPath {
            from: start,
            to: goal,
        })
    }

    /// The route through `waypoints` in order, each pair joined by its fewest-edge way.
    pub fn route(&self, waypoints: &[TagId], blocked: &Blocked) -> Result<Route, RouteError> {
        let Some(&first) = waypoints.first() else {
            return Ok(Route {
                tags: Vec::new(),
                legs: Vec::new(),
            });
        };
        if !self.tags.contains_key(&first) {
            return Err(RouteError::UnknownTag(first));
        }
        let mut tags = vec![first];
        for pair in waypoints.windows(2) {
            let path = self.find_path(pair[0], pair[1], blocked)?;
            tags.extend(path.into_iter().skip(1));
        }
        let legs = tags
            .windows(2)
            .map(|p| {
                let edge = self.edge(p[0], p[1]).expect("BFS walks the map's edges");
                Leg {
                    from: p[0],
                    to: p[1],
                    direction: edge.direction,
                    kind: edge.kind,
                }
            })
            .collect();
        Ok(Route { tags, legs })
    }

    /// A task's route, by its name.
    pub fn task_route(&self, name: &str, blocked: &Blocked) -> Option<Result<Route, RouteError>> {
        let waypoints = self.tasks.get(name)?;
        Some(self.route(waypoints, blocked))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A square of four tags with a diagonal-free shortcut: 508 -> 1 -> 2 -> 3, and
    /// 508 -> 4 -> 3; every edge also back.
    const SQUARE: &str = "
tags:
  508: {x: 0, y: 0, type: dock, zone: DOCK}
  1: {x: 1, y: 0, type: waypoint, zone: A}
  2: {x: 2, y: 0, type: pivot, zone: A}
  3: {x: 2, y: 1, type: shelf, zone: B}
  4: {x: 0, y: 1, type: pivot, zone: B}
edges:
  508:
    - {to: 1, direction: forward, type: straight}
    - {to: 4, direction: forward, type: pivot}
  1:
    - {to: 2, direction: forward, type: straight}
    - {to: 508, direction: backward, type: straight}
  2:
    - {to: 3, direction: forward, type: pivot}
  4:
    - {to: 3, direction: forward, type: pivot}
  3:
    - {to: 2, direction: backward, type: straight}
";

    fn square() -> TagMap {
        TagMap::parse(SQUARE).unwrap()
    }

    #[test]
    fn bfs_takes_the_fewest_edges_and_the_first_listed_of_equals() {
        let m = square();
        let none = Blocked::new();
        // 508 -> 4 -> 3 (2 edges) beats 508 -> 1 -> 2 -> 3 (3 edges).
        assert_eq!(m.find_path(508, 3, &none).unwrap(), vec![508, 4, 3]);
        assert_eq!(m.find_path(508, 2, &none).unwrap(), vec![508, 1, 2]);
        assert_eq!(m.find_path(3, 3, &none).unwrap(), vec![3]);
    }

    #[test]
    fn a_blocked_edge_is_routed_round_and_a_cut_graph_says_where() {
        let m = square();
        let blocked: Blocked = [(508, 4)].into();
        assert_eq!(m.find_path(508, 3, &blocked).unwrap(), vec![508, 1, 2, 3]);
        // Edges are one way: nothing leads back from 3 to the dock but 3 -> 2 -> ?; 2 has
        // no edge to 1.
        assert_eq!(
            m.find_path(3, 508, &Blocked::new()),
            Err(RouteError::NoPath { from: 3, to: 508 })
        );
        assert_eq!(
            m.find_path(508, 99, &Blocked::new()),
            Err(RouteError::UnknownTag(99))
        );
    }

    #[test]
    fn a_route_joins_its_waypoints_and_carries_each_legs_direction() {
        let m = square();
        let r = m.route(&[508, 2, 3], &Blocked::new()).unwrap();
        assert_eq!(r.tags, vec![508, 1, 2, 3]);
        let kinds: Vec<_> = r.legs.iter().map(|l| (l.from, l.to, l.kind)).collect();
        assert_eq!(
            kinds,
            vec![
                (508, 1, EdgeKind::Straight),
                (1, 2, EdgeKind::Straight),
                (2, 3, EdgeKind::Pivot)
            ]
        );
        let back = m.route(&[1, 508], &Blocked::new()).unwrap();
        assert_eq!(back.legs[0].direction, Direction::Backward);
    }
}
