//! Nav2 map files: hostile headers and images.

use super::{Case, case};

/// A valid Nav2 map header naming `image`, with `extra` lines.
fn map_yaml(image: &str, resolution: &str, extra: &str) -> String {
    format!(
        "image: {image}\nresolution: {resolution}\norigin: [0.0, 0.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n{extra}"
    )
}

pub fn cases() -> Vec<Case> {
    let info = ["map", "info", "m.yaml"];
    let pgm = b"P5 4 4 255\n"
        .iter()
        .copied()
        .chain([254u8; 16])
        .collect::<Vec<u8>>();
    let map = |names: &str, yaml: String| {
        case("map", &info, names)
            .file("m.yaml", yaml)
            .file("m.pgm", pgm.clone())
    };
    vec![
        map("resolution", map_yaml("m.pgm", "1e308", "")),
        map("resolution", map_yaml("m.pgm", "nan", "")),
        map("resolution", map_yaml("m.pgm", "-0.05", "")),
        map("resolution", map_yaml("m.pgm", "1e-300", "")),
        map(
            "origin",
            map_yaml("m.pgm", "0.05", "").replace("[0.0, 0.0, 0.0]", "[1e308, 0, 0]"),
        ),
        map(
            "limit",
            format!(
                "image: {}m.pgm{}\n",
                "[".repeat(100_000),
                "]".repeat(100_000)
            ),
        ),
        map(
            "nested",
            format!("image: {}m.pgm{}\n", "[".repeat(10_000), "]".repeat(10_000)),
        ),
        map(
            "m.yaml",
            "image: m.pgm\n".to_string() + &"  ".repeat(40_000) + "x: 1\n",
        ),
        map("/dev/zero", map_yaml("/dev/zero", "0.05", "")),
        map(
            "free_thresh",
            map_yaml("m.pgm", "0.05", "").replace("0.196", "nan"),
        ),
        map(
            "negate",
            map_yaml("m.pgm", "0.05", "").replace("negate: 0", "negate: 7"),
        ),
        case("map", &info, "width")
            .file("m.yaml", map_yaml("m.pgm", "0.05", ""))
            .file("m.pgm", b"P5 20000 20000 255\n".to_vec()),
        case("map", &info, "truncated")
            .file("m.yaml", map_yaml("m.pgm", "0.05", ""))
            .file("m.pgm", b"P2 8000 8000 255\n1 2 3".to_vec()),
        case("map", &["map", "info", "/dev/zero"], "/dev/zero"),
        case("map", &["map", "info", "{dir}"], "regular file"),
        case(
            "map",
            &[
                "plan", "--map", "m.yaml", "--from", "0,0", "--to", "0.1,0.1",
            ],
            "resolution",
        )
        .file("m.yaml", map_yaml("m.pgm", "1e308", ""))
        .file("m.pgm", pgm.clone()),
        // Continuing lidar SLAM's map: the pose graph beside it, missing or bad.
        continued("m.posegraph.json", None),
        continued("nodes[0].pose x", Some(graph("[1e308, 0, 0]", "[]"))),
        continued(
            "nodes",
            Some(r#"{"format":"navdeck pose graph","version":1,"edges":[]}"#.into()),
        ),
        continued("edges[0]", Some(graph("[0, 0, 0]", EDGE_TO_NOWHERE))),
        continued(
            "format",
            Some(graph("[0, 0, 0]", "[]").replace("navdeck pose graph", "cartographer")),
        ),
    ]
}

/// An edge from the one node to a node the graph does not have.
const EDGE_TO_NOWHERE: &str =
    r#"[{"from":0,"to":5,"kind":"sequential","relative":[0,0,0],"information":[1,0,0,1,0,1]}]"#;

/// A one-node pose graph file with the node's `pose` and `edges`.
fn graph(pose: &str, edges: &str) -> String {
    format!(
        r#"{{"format":"navdeck pose graph","version":1,"nodes":[{{"pose":{pose},"angle_min":0,"angle_increment":0.1,"range_min":0.1,"range_max":3.5,"ranges":[1.0,null]}}],"edges":{edges}}}"#
    )
}

/// `navdeck mission --estimator slam --map m.yaml` with `graph` as m.posegraph.json
/// (none: missing); the refusal names `names`.
fn continued(names: &str, graph: Option<String>) -> Case {
    let args = ["mission", "--estimator", "slam", "--map", "m.yaml"];
    let pgm: Vec<u8> = b"P5 4 4 255\n".iter().copied().chain([254u8; 16]).collect();
    let c = case("map", &args, names)
        .file("m.yaml", map_yaml("m.pgm", "0.05", ""))
        .file("m.pgm", pgm);
    match graph {
        Some(g) => c.file("m.posegraph.json", g),
        None => c,
    }
}
