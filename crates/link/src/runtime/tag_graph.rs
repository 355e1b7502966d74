//! Route mode's tag graph for a link that shows it (RViz over ROS 2): the tag map's tags
//! and edges, the route being driven and its leg, and the edges found blocked, as the
//! console's map draws them (`tui/widgets/tag_graph.rs`).

use crate::TagGraphPicture;
use navdeck_core::geometry::Point2;
use navdeck_pilot::tag_route::TagRouting;

/// The graph when a tag map is laid, else None. The route is the one being driven (none
/// once the run is done or failed); blocked edges stay as long as the run does.
pub(super) fn picture(routing: &TagRouting) -> Option<TagGraphPicture> {
    let map = routing.map()?;
    let run = routing.run();
    let driving = run.filter(|_| routing.driving());
    Some(TagGraphPicture {
        tags: (map.tags.iter())
            .map(|(&id, t)| (id, Point2::new(t.x, t.y)))
            .collect(),
        edges: (map.edges.iter())
            .flat_map(|(&from, list)| list.iter().map(move |e| (from, e.to)))
            .collect(),
        route: driving.map_or_else(Vec::new, |r| r.route().tags.clone()),
        leg: driving.and(routing.current_leg()).map(|(leg, _, _)| leg),
        blocked: run.map_or_else(Vec::new, |r| r.blocked_edges().to_vec()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::runtime::Runtime;
    use crate::{LinkError, Picture, RobotLink, SensorFrame};
    use navdeck_core::data::Command;
    use navdeck_core::tags::TagMap;
    use navdeck_core::tags::drive::DriveSetup;
    use navdeck_pilot::Intent;
    use navdeck_pilot::config::Settings;
    use navdeck_pilot::tag_route::TagGoal;
    use std::sync::{Arc, Mutex};

    /// Three tags in a row east of the dock, each edge both ways.
    const MAP: &str = "tags:
  1: {x: 0.0, y: 0.0, type: dock, zone: DOCK}
  2: {x: 0.5, y: 0.0, type: waypoint, zone: A}
  3: {x: 1.0, y: 0.0, type: waypoint, zone: A}
edges:
  1: [{to: 2, direction: forward, type: straight}]
  2: [{to: 1, direction: backward, type: straight}, {to: 3, direction: forward, type: straight}]
  3: [{to: 2, direction: backward, type: straight}]
";

    /// A robot that reports nothing and keeps every picture it is shown, wanting the
    /// full picture every second.
    struct Shown(Arc<Mutex<Vec<Picture>>>);

    impl RobotLink for Shown {
        fn label(&self) -> String {
            "shown".into()
        }
        fn send(&mut self, _: &Command) -> Result<(), LinkError> {
            Ok(())
        }
        fn poll(&mut self, _: f64) -> Result<SensorFrame, LinkError> {
            Ok(SensorFrame::default())
        }
        fn stop(&mut self) {}
        fn picture_period(&self) -> Option<f64> {
            Some(1.0)
        }
        fn show(&mut self, picture: &Picture) {
            self.0.lock().unwrap().push(picture.clone());
        }
    }

    fn graphs(shown: &Mutex<Vec<Picture>>) -> Vec<Option<TagGraphPicture>> {
        let list = std::mem::take(&mut *shown.lock().unwrap());
        list.into_iter().map(|p| p.tag_graph).collect()
    }

    #[test]
    fn the_full_picture_carries_the_laid_map_and_the_route_being_driven() {
        let shown = Arc::new(Mutex::new(Vec::new()));
        let link = Box::new(Shown(shown.clone()));
        let mut robot = Runtime::new(link, Settings::default(), 0.0);
        robot.tick(0.0, Vec::new());
        // No tag map: no graph, not even at the full period.
        assert!(!graphs(&shown).is_empty());
        assert!(graphs(&shown).iter().all(Option::is_none));

        let map = Arc::new(TagMap::parse(MAP).unwrap());
        let setup = DriveSetup::default();
        robot.pilot_mut().set_tag_map(Some(map), setup);
        robot.tick(1.0, vec![Intent::TagRoute(TagGoal::Tag(3))]);
        let shown_now = graphs(&shown);
        // Only the full picture carries it.
        let full: Vec<&TagGraphPicture> = shown_now.iter().flatten().collect();
        assert_eq!(full.len(), 1, "{shown_now:?}");
        assert!(shown_now.len() > 1, "{shown_now:?}");
        robot.tick(2.0, Vec::new());
        let g = graphs(&shown).into_iter().flatten().last().unwrap();
        assert_eq!(g.tags.len(), 3);
        assert_eq!(g.edges, vec![(1, 2), (2, 1), (2, 3), (3, 2)]);
        assert_eq!(g.route, vec![1, 2, 3]);
        assert_eq!(g.leg, Some(0));
        assert_eq!(g.next(), Some(2));
        assert!(g.blocked.is_empty());
    }
}
