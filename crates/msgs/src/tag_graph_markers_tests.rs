use super::*;

/// Four tags in a square (101 at the origin, 102 east, 103 north-east, 104 north), its
/// sides as edges both ways, the route 101 → 102 → 103 on its second leg, and the edge
/// 101-104 found blocked.
fn square() -> TagGraphPicture {
    let tags = vec![
        (101, Point2::new(0.0, 0.0)),
        (102, Point2::new(1.0, 0.0)),
        (103, Point2::new(1.0, 1.0)),
        (104, Point2::new(0.0, 1.0)),
    ];
    let sides = [(101, 102), (102, 103), (103, 104), (104, 101)];
    let edges = sides.iter().flat_map(|&(a, b)| [(a, b), (b, a)]).collect();
    TagGraphPicture {
        tags,
        edges,
        route: vec![101, 102, 103],
        leg: Some(1),
        blocked: vec![(101, 104)],
    }
}

fn find<'a>(m: &'a [MarkerHumble], ns: &str, id: i32) -> Option<&'a MarkerHumble> {
    m.iter().find(|k| k.ns == ns && k.id == id)
}

fn xy(points: &[Vector3]) -> Vec<(f64, f64)> {
    points.iter().map(|p| (p.x, p.y)).collect()
}

#[test]
fn a_graph_becomes_deleteall_five_shapes_and_a_label_a_tag() {
    let m = tag_graph_markers(&square(), Time::default(), "map");
    // DELETEALL, tags, edges, route, blocked, next, and four labels.
    assert_eq!(m.len(), 1 + 5 + 4);
    assert_eq!(m[0].action, msgs::MARKER_DELETEALL);
    assert!(m.iter().all(|k| k.header.frame_id == "map"));
    assert!(m[1..].iter().all(|k| k.action == msgs::MARKER_ADD));

    let tags = find(&m, NS, ID_TAGS).unwrap();
    assert_eq!(tags.kind, msgs::MARKER_CUBE_LIST);
    assert_eq!((tags.scale.x, tags.scale.y), (TAG_SIDE, TAG_SIDE));
    assert_eq!(tags.points.len(), 4);
    // One colour a tag: those on the route green, 104 not.
    assert_eq!(tags.colors.len(), 4);
    assert_eq!(tags.colors[0], colour(GREEN));
    assert_eq!(tags.colors[3], colour(LIGHT));

    let edges = find(&m, NS, ID_EDGES).unwrap();
    assert_eq!(edges.kind, msgs::MARKER_LINE_LIST);
    assert_eq!(edges.points.len(), 2 * 8);
    assert_eq!(edges.color, colour(GREY));

    let labels: Vec<&MarkerHumble> = m.iter().filter(|k| k.ns == NS_IDS).collect();
    assert_eq!(labels.len(), 4);
    for (label, id) in labels.iter().zip([101, 102, 103, 104]) {
        assert_eq!(label.kind, msgs::MARKER_TEXT_VIEW_FACING);
        assert_eq!(
            (label.id, label.text.as_str()),
            (id, id.to_string().as_str())
        );
    }
    assert_eq!(
        (labels[2].pose.position.x, labels[2].pose.position.y),
        (1.0, 1.0)
    );
}

#[test]
fn the_route_is_a_thick_green_strip_through_its_tags_in_order() {
    let m = tag_graph_markers(&square(), Time::default(), "map");
    let route = find(&m, NS, ID_ROUTE).unwrap();
    assert_eq!(route.kind, msgs::MARKER_LINE_STRIP);
    assert_eq!(xy(&route.points), vec![(0.0, 0.0), (1.0, 0.0), (1.0, 1.0)]);
    assert_eq!(route.color, colour(GREEN));
    let edges = find(&m, NS, ID_EDGES).unwrap();
    assert!(route.scale.x > edges.scale.x);
    // Drawn above the plain edges.
    assert!(route.points[0].z > edges.points[0].z);
}

#[test]
fn a_blocked_edge_is_red_and_the_next_tag_is_ringed() {
    let m = tag_graph_markers(&square(), Time::default(), "map");
    let blocked = find(&m, NS, ID_BLOCKED).unwrap();
    assert_eq!(blocked.kind, msgs::MARKER_LINE_LIST);
    assert_eq!(blocked.color, colour(RED));
    assert_eq!(xy(&blocked.points), vec![(0.0, 0.0), (0.0, 1.0)]);
    // Leg 1 runs 102 → 103: the robot heads for 103.
    let next = find(&m, NS, ID_NEXT).unwrap();
    assert_eq!(next.kind, msgs::MARKER_CUBE);
    assert_eq!((next.pose.position.x, next.pose.position.y), (1.0, 1.0));
    assert!(next.scale.x > TAG_SIDE);
}

#[test]
fn ids_stay_the_same_from_one_call_to_the_next() {
    let key = |m: &[MarkerHumble]| -> Vec<(String, i32, i32)> {
        m.iter().map(|k| (k.ns.clone(), k.id, k.kind)).collect()
    };
    let mut g = square();
    let first = tag_graph_markers(&g, Time::default(), "map");
    let later = Time {
        sec: 12,
        nanosec: 5,
    };
    let again = tag_graph_markers(&g, later, "map");
    assert_eq!(key(&first), key(&again));
    // The robot on the route's first leg: the same markers, the ring on 102.
    g.leg = Some(0);
    let on = tag_graph_markers(&g, later, "map");
    assert_eq!(key(&first), key(&on));
    let next = find(&on, NS, ID_NEXT).unwrap();
    assert_eq!((next.pose.position.x, next.pose.position.y), (1.0, 0.0));
}

#[test]
fn without_a_route_or_blocks_only_the_tags_edges_and_labels_are_drawn() {
    let g = TagGraphPicture {
        route: Vec::new(),
        leg: None,
        blocked: Vec::new(),
        ..square()
    };
    let m = tag_graph_markers(&g, Time::default(), "map");
    assert_eq!(m.len(), 1 + 2 + 4);
    for id in [ID_ROUTE, ID_BLOCKED, ID_NEXT] {
        assert!(find(&m, NS, id).is_none(), "marker {id} drawn");
    }
    assert!((find(&m, NS, ID_TAGS).unwrap().colors.iter()).all(|c| *c == colour(LIGHT)));
    // An empty graph clears the display and draws nothing.
    let none = tag_graph_markers(&TagGraphPicture::default(), Time::default(), "map");
    assert_eq!(none.len(), 1);
    assert_eq!(none[0].action, msgs::MARKER_DELETEALL);
}

#[test]
fn an_edge_or_route_tag_the_graph_lacks_is_left_out() {
    let g = TagGraphPicture {
        edges: vec![(101, 102), (102, 999)],
        route: vec![101, 999, 102],
        leg: Some(0),
        blocked: vec![(999, 101)],
        ..square()
    };
    let m = tag_graph_markers(&g, Time::default(), "map");
    assert_eq!(find(&m, NS, ID_EDGES).unwrap().points.len(), 2);
    assert_eq!(
        xy(&find(&m, NS, ID_ROUTE).unwrap().points),
        vec![(0.0, 0.0), (1.0, 0.0)]
    );
    assert!(find(&m, NS, ID_BLOCKED).is_none());
    // The leg ends on a tag not in the graph: no ring.
    assert!(find(&m, NS, ID_NEXT).is_none());
}
