//! `navdeck tags`: read a tag map (seed 003's `map.yaml`), and plan routes through it.

use anyhow::{Context, Result};
use navdeck::tags::{Route, TagId, TagMap, scan};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(Debug, clap::Subcommand)]
pub(crate) enum TagsCommand {
    /// Check a tag map: tags, edges, tasks; print its size, or the first fault with its line.
    Check { map: PathBuf },
    /// The BFS route from a tag (default: the dock) to a tag, or through a task.
    Route {
        map: PathBuf,
        /// Where the route starts (default: the dock).
        #[arg(long, value_name = "TAG")]
        from: Option<TagId>,
        /// The tag to reach.
        #[arg(
            long,
            value_name = "TAG",
            conflicts_with = "task",
            required_unless_present = "task"
        )]
        to: Option<TagId>,
        /// A task of the map, by name.
        #[arg(long, value_name = "NAME")]
        task: Option<String>,
        /// Edges the route may not use, FROM-TO (repeatable).
        #[arg(long, value_name = "FROM-TO", value_parser = edge)]
        blocked: Vec<(TagId, TagId)>,
        /// Print one JSON object.
        #[arg(long)]
        json: bool,
    },
    /// The route from the dock through a scan list's groups and back (seed 003 §2.2: a
    /// CSV with a group_id column; tag = 100 + group id).
    RouteFromScan {
        map: PathBuf,
        csv: PathBuf,
        /// Print one JSON object.
        #[arg(long)]
        json: bool,
    },
}

/// "101-117" as the edge 101 -> 117.
pub(crate) fn edge(text: &str) -> Result<(TagId, TagId), String> {
    let (a, b) = text
        .split_once('-')
        .ok_or_else(|| format!("{text:?}: give an edge as FROM-TO, e.g. 104-117"))?;
    let tag = |s: &str| {
        s.trim()
            .parse::<TagId>()
            .map_err(|_| format!("{text:?}: {s:?} is no tag id"))
    };
    Ok((tag(a)?, tag(b)?))
}

/// The tag map in `path` (read bounded, as the console's `--tags` reads it).
pub(crate) fn load(path: &Path) -> Result<TagMap> {
    navdeck::session::load_tag_map(path)
}

fn route_json(route: &Route) -> serde_json::Value {
    let legs: Vec<_> = (route.legs.iter())
        .map(|l| {
            serde_json::json!({
                "from": l.from, "to": l.to,
                "direction": format!("{:?}", l.direction).to_lowercase(),
                "type": format!("{:?}", l.kind).to_lowercase(),
            })
        })
        .collect();
    serde_json::json!({ "tags": route.tags, "legs": legs })
}

fn route_text(route: &Route) -> String {
    let tags: Vec<String> = route.tags.iter().map(|t| t.to_string()).collect();
    format!("{} ({} legs)", tags.join(" -> "), route.legs.len())
}

pub(crate) fn run(command: &TagsCommand) -> Result<ExitCode> {
    match command {
        TagsCommand::Check { map } => {
            let m = load(map)?;
            let edges: usize = m.edges.values().map(Vec::len).sum();
            sayln!(
                "{}: {} tags, {} edges, {} tasks, dock {}",
                map.display(),
                m.tags.len(),
                edges,
                m.tasks.len(),
                m.dock
            );
        }
        TagsCommand::Route {
            map,
            from,
            to,
            task,
            blocked,
            json,
        } => {
            let m = load(map)?;
            let blocked = blocked.iter().copied().collect();
            let route = match (task, to) {
                (Some(name), _) => {
                    let names: Vec<&str> = m.tasks.keys().map(String::as_str).collect();
                    m.task_route(name, &blocked).with_context(|| {
                        format!("no task {name:?} (tasks: {})", names.join(", "))
                    })?
                }
                (None, Some(to)) => m.route(&[from.unwrap_or(m.dock), *to], &blocked),
                (None, None) => unreachable!("clap requires --to or --task"),
            }?;
            if *json {
                sayln!("{}", route_json(&route));
            } else {
                sayln!("{}", route_text(&route));
            }
        }
        TagsCommand::RouteFromScan { map, csv, json } => {
            let m = load(map)?;
            let text = std::fs::read_to_string(csv)
                .with_context(|| format!("reading scan list {}", csv.display()))?;
            let r = scan::route_from_scan(&m, &text)
                .with_context(|| format!("scan list {}", csv.display()))?;
            if *json {
                let mut v = route_json(&r.route);
                v["scan_tags"] = serde_json::json!(r.scan_tags);
                v["waypoints"] = serde_json::json!(r.waypoints);
                sayln!("{v}");
            } else {
                let scans: Vec<String> = r.scan_tags.iter().map(|t| t.to_string()).collect();
                sayln!("scan {}: {}", scans.join(", "), route_text(&r.route));
            }
        }
    }
    Ok(ExitCode::SUCCESS)
}
