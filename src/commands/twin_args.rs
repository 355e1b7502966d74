//! The console's options for the twin (part of the binary, beside main.rs): its world,
//! where it starts, its noise seed, its floor tags, its camera and the faults injected
//! into it.

use super::args::{parse_pose, whole};
use navdeck::geometry::Pose2;
use navdeck::sim::FaultSpec;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub(crate) struct TwinArgs {
    /// World for the twin: a world file (TOML, see maps/) or a Nav2 map (map_server
    /// YAML + PGM, its occupied cells walls); default: the built-in arena.
    #[arg(long, value_name = "FILE")]
    pub world: Option<PathBuf>,

    /// Where the twin's robot starts, metres and degrees in the world's frame, instead
    /// of the world's own start (a Nav2 map's is its roomiest free cell).
    #[arg(long, value_name = "X,Y,THETA_DEG", value_parser = parse_pose, allow_hyphen_values = true)]
    pub start: Option<Pose2>,

    /// Seed for the twin's sensor noise: the same seed replays the same run.
    #[arg(
        long,
        default_value_t = 1,
        value_name = "N",
        allow_negative_numbers = true,
        value_parser = whole::<u64>
    )]
    pub seed: u64,

    /// A tag map (seed 003's map.yaml shape, e.g. maps/tag_warehouse.yaml) laid on the
    /// twin's floor, seen by its ideal tag camera: route mode (i) drives its tasks. Without
    /// --world the twin's world is built round the tags, the robot on the dock. With
    /// --link ros2 the robot's own camera reads the tags ([ros2.tags]: rgb, camera_info).
    #[arg(long, value_name = "FILE")]
    pub tags: Option<PathBuf>,

    /// The twin sees through a rendered camera and OpenCV's ArUco detector instead of its
    /// ideal marker sensor (needs a build with `--features vision`).
    #[arg(long)]
    pub sim_camera: bool,

    /// A fault injected into the twin, on simulated time: KIND@START[+DURATION][:PARAM]
    /// with KIND camera (dark), lidar, odom (silent), arm (not answering) or slip (the
    /// wheels deliver PARAM of the commanded travel, default 0.5), e.g. camera@60+20 or
    /// slip@30+10:0.5; no +DURATION lasts to the end. START may be a window A..B
    /// (camera@30..180+20): the start is drawn from the run's seed. May be given again.
    #[arg(long, value_name = "KIND@START[+DURATION][:PARAM]")]
    pub fault: Vec<FaultSpec>,
}
