//! `navdeck ros2 robots`: the robots on a ROS 2 domain, found by what they publish and
//! read (Odometry on `odom`, Twist or TwistStamped on `cmd_vel`), one row a namespace:
//! what a user running several TurtleBot3s under `/tb3_0`, `/tb3_1`, ... passes to
//! `--ns`.

use anyhow::Result;
use navdeck::link::ros2::graph::robots::{RobotRow, robots as find};
use serde::Serialize;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

/// `navdeck ros2 robots`.
#[derive(Debug, clap::Args)]
pub struct RobotsArgs {
    /// DDS domain ID (default: ROS_DOMAIN_ID, else 0).
    #[arg(long, value_name = "N", value_parser = super::args::parse_domain)]
    domain: Option<u16>,
    /// The [ros2] section (e.g. `interfaces`), as for `--link ros2`.
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
    /// Seconds to listen: discovery and odometry's rate are taken over this time.
    #[arg(long, default_value_t = 2.0, value_name = "SECONDS",
          value_parser = super::ros2::parse_duration, allow_negative_numbers = true)]
    duration: f64,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
}

/// What `--json` prints.
#[derive(Serialize)]
struct Report {
    domain: u16,
    duration_s: f64,
    robots: Vec<RobotRow>,
}

pub fn robots(args: &RobotsArgs) -> Result<ExitCode> {
    let (listener, now, domain) = super::ros2::listen(
        args.config.as_deref(),
        None,
        args.domain,
        args.duration,
        false,
    )?;
    let rows = find(&listener.endpoints(), &listener.rates(now));
    if args.json {
        let report = Report {
            domain,
            duration_s: args.duration,
            robots: rows,
        };
        sayln!("{}", serde_json::to_string(&report)?);
    } else if rows.is_empty() {
        sayln!(
            "no robots in DDS domain {domain} after {:.1} s: nothing publishes Odometry on odom or reads cmd_vel (check --domain, ROS_DOMAIN_ID and [ros2] interfaces)",
            args.duration
        );
    } else {
        say!("{}", table(&rows));
    }
    Ok(ExitCode::SUCCESS)
}

/// The robots as an aligned table, with the `--ns` to drive each.
fn table(rows: &[RobotRow]) -> String {
    let mut cells = vec![
        [
            "NAMESPACE",
            "ODOM HZ",
            "CMD_VEL",
            "SCAN",
            "CAMERA",
            "DRIVE WITH",
        ]
        .map(String::from)
        .to_vec(),
    ];
    let yes = |b: bool| if b { "yes" } else { "-" }.to_string();
    for r in rows {
        let odom = match (r.odom_publishers, r.odom_rate_hz) {
            (0, _) => "-".to_string(),
            (_, Some(hz)) => format!("{hz:.1}"),
            (_, None) => "?".to_string(),
        };
        let cmd_vel: Vec<&str> = (r.cmd_vel_types.iter())
            .map(|t| t.rsplit('/').next().unwrap_or(t))
            .collect();
        let ns = if r.namespace == "/" {
            "--link ros2".to_string()
        } else {
            format!("--link ros2 --ns {}", r.namespace)
        };
        cells.push(vec![
            r.namespace.clone(),
            odom,
            if cmd_vel.is_empty() {
                "-".into()
            } else {
                cmd_vel.join(", ")
            },
            yes(r.scan),
            yes(r.camera),
            ns,
        ]);
    }
    super::ros2::aligned(&cells, &[1])
}
