//! How a session places the robot: the EKF alone, MCL on a known map, or lidar SLAM,
//! fresh or continuing a saved pose graph.

use super::{Robot, SessionSpec, is_nav2_map};
use crate::config::Config;
use crate::pilot::localize::{InitialPose, Localizer};
use crate::slam::lidar::SavedGraph;
use crate::slam::lidar::saved::SUFFIX;
use crate::slam::mcl::config::Estimator;
use anyhow::{Result, bail};
use std::path::{Path, PathBuf};

/// MCL's map and start for `spec`, or lidar SLAM's saved map to continue, or None when
/// the EKF (or lidar SLAM from nothing) places the robot. The command
/// line's estimator overrides the config's and is written back into it.
pub(super) fn localizer_for(
    spec: &SessionSpec,
    config: &mut Config,
    robot: &Robot,
) -> Result<Option<Localizer>> {
    let choice = &spec.localize;
    if let Some(e) = choice.estimator {
        config.localization.estimator = e;
    }
    let start = |given: Option<InitialPose>| match (given, robot) {
        (Some(initial), _) => initial,
        // The twin starts where its world says, as the EKF does; a real robot is looked
        // for (MCL) or starts the map at the origin (lidar SLAM).
        (None, Robot::Twin(twin)) => InitialPose::At(twin.pose()),
        (None, Robot::Link(_)) => InitialPose::Unknown,
    };
    match (config.localization.estimator, &choice.map) {
        (Estimator::Mcl, _) => {}
        (Estimator::Slam, Some(map)) => {
            let initial = start(choice.initial_pose);
            return continuing(map, initial, config).map(Some);
        }
        (Estimator::Slam, None) if choice.initial_pose.is_some() => {
            bail!(
                "--initial-pose is for MCL, or for lidar SLAM continuing a saved map: \
                 add --map FILE.yaml (saved with its FILE.posegraph.json)"
            );
        }
        _ => {
            if choice.map.is_some() || choice.initial_pose.is_some() {
                bail!(
                    "--map and --initial-pose are for MCL (--estimator mcl) or for lidar SLAM \
                     continuing a saved map (--estimator slam)"
                );
            }
            return Ok(None);
        }
    }
    let nav2_world = spec.world.as_ref().filter(|w| is_nav2_map(w));
    let Some(path) = choice.map.as_ref().or(nav2_world) else {
        bail!(
            "the MCL estimator needs a map to localise on: --map FILE.yaml (a Nav2 map), \
             or a Nav2 map as the twin's --world"
        );
    };
    let map = crate::map::io::load(path).map_err(|e| {
        anyhow::anyhow!("cannot use map {} for MCL: {}", path.display(), e.reason())
    })?;
    let initial = start(choice.initial_pose);
    let localizer = Localizer::new(
        map.grid,
        initial,
        spec.seed,
        path.display().to_string(),
        &config.map,
    )
    .map_err(anyhow::Error::msg)?;
    Ok(Some(localizer))
}

/// The most bytes a pose graph file may hold: `MAX_NODES` keyframes of 360 beams are
/// about 150 MB of JSON (crates/core/src/slam/lidar/saved.rs), with room to spare.
const GRAPH_LIMIT: u64 = 256 << 20;

/// The pose graph saved beside the Nav2 map `map` (`NAME.yaml` → `NAME.posegraph.json`).
pub fn graph_beside(map: &Path) -> PathBuf {
    map.with_extension(SUFFIX)
}

/// Lidar SLAM continuing the graph saved beside `map`, from `initial`; a missing or bad
/// file is refused in one sentence naming it and the field at fault.
pub fn continuing(map: &Path, initial: InitialPose, config: &Config) -> Result<Localizer> {
    let grid = crate::map::io::load(map)
        .map_err(|e| {
            anyhow::anyhow!(
                "cannot continue mapping on {}: {}",
                map.display(),
                e.reason()
            )
        })?
        .grid;
    let file = graph_beside(map);
    let graph = read_graph(&file).map_err(|why| {
        anyhow::anyhow!(
            "cannot continue mapping on {}: pose graph {}: {why}",
            map.display(),
            file.display()
        )
    })?;
    Localizer::continuing(
        grid,
        initial,
        map.display().to_string(),
        (graph, file.display().to_string()),
        &config.map,
    )
    .map_err(anyhow::Error::msg)
}

/// A saved pose graph, read bounded and checked; the error names the field and value.
pub fn read_graph(file: &Path) -> std::result::Result<SavedGraph, String> {
    let text = crate::data::files::read_text_limited(file, GRAPH_LIMIT).map_err(|e| {
        match e.kind() {
            std::io::ErrorKind::NotFound => {
                "no such file (it is saved beside the map with the map, by S or --save-map while lidar SLAM runs)".to_string()
            }
            _ => e.to_string(),
        }
    })?;
    SavedGraph::from_json(&text)
}
