//! Building a session from the command line's choices: config, keymap, world, link.
//! Everything is loaded and checked here, before the terminal is touched.

use crate::app::App;
use crate::config::Config;
use crate::keymap::Keymap;
use crate::link::RobotLink;
use crate::link::ros2::{Ros2Link, Ros2Options, domain_from};
use crate::link::serial::SerialLink;
use crate::link::sim::SimLink;
use crate::sim::{Twin, World};
use anyhow::{Context, Result, bail};
use std::path::PathBuf;

/// Which robot to drive.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LinkChoice {
    Sim,
    Ros2(Ros2Target),
    Serial(String),
}

/// The command line's say on where the ROS 2 robot is: over the config file, and for the
/// domain over ROS_DOMAIN_ID.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Ros2Target {
    pub namespace: Option<String>,
    pub domain: Option<u16>,
}

impl std::str::FromStr for LinkChoice {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "sim" => Ok(LinkChoice::Sim),
            "ros2" => Ok(LinkChoice::Ros2(Ros2Target::default())),
            _ => match s.strip_prefix("serial:") {
                Some(path) if !path.is_empty() => Ok(LinkChoice::Serial(path.to_string())),
                _ => Err(format!(
                    "unknown link {s:?}: expected sim, ros2 or serial:PATH[@BAUD]"
                )),
            },
        }
    }
}

/// The choices a session is built from.
#[derive(Clone, Debug)]
pub struct SessionSpec {
    pub world: Option<PathBuf>,
    pub seed: u64,
    pub config: Option<PathBuf>,
    pub keymap: Option<PathBuf>,
    pub link: LinkChoice,
}

/// A loaded, validated session, ready for the TUI or the headless runner.
pub struct Session {
    pub config: Config,
    pub keymap: Keymap,
    pub link: Box<dyn RobotLink>,
}

impl Session {
    pub fn load(spec: &SessionSpec) -> Result<Session> {
        let config = match &spec.config {
            Some(path) => Config::load(path)?,
            None => Config::default(),
        };
        let keymap = match &spec.keymap {
            Some(path) => Keymap::load(path)?,
            None => Keymap::default_map(),
        };
        let link: Box<dyn RobotLink> = match &spec.link {
            LinkChoice::Sim => {
                let world = match &spec.world {
                    Some(path) => World::load(path)
                        .with_context(|| format!("cannot use world {}", path.display()))?,
                    None => World::default_arena(),
                };
                let twin = Twin::new(world, &config, spec.seed);
                Box::new(SimLink::new(twin, 0.0))
            }
            LinkChoice::Ros2(target) => {
                let mut ros2 = config.ros2.clone();
                if let Some(ns) = &target.namespace {
                    ros2.namespace = ns.clone();
                }
                let domain = domain_from(target.domain, std::env::var("ROS_DOMAIN_ID").ok())
                    .map_err(anyhow::Error::msg)?;
                let link = Ros2Link::connect(Ros2Options {
                    config: ros2,
                    domain,
                    track: config.robot.track,
                })
                .context("cannot open the ROS 2 link")?;
                Box::new(link)
            }
            LinkChoice::Serial(spec) => Box::new(SerialLink::open(spec, &config)?),
        };
        Ok(Session {
            config,
            keymap,
            link,
        })
    }

    /// Makes the twin see through a rendered camera and the ArUco detector instead of
    /// its ideal marker sensor (`--sim-camera`). Refused with a clear message when navdeck
    /// was built without the `vision` feature or the link has no twin.
    pub fn use_sim_camera(
        &mut self,
        stopwatch: Option<std::sync::Arc<dyn crate::perception::stopwatch::Stopwatch>>,
    ) -> Result<()> {
        #[cfg(feature = "vision")]
        {
            let vision = self.config.vision.clone();
            let Some(twin) = self.link.twin_mut() else {
                bail!("--sim-camera needs the twin (--link sim)");
            };
            twin.use_rendered_camera(&vision, stopwatch)
                .context("cannot start the rendered camera")?;
            Ok(())
        }
        #[cfg(not(feature = "vision"))]
        {
            let _ = stopwatch;
            bail!(
                "--sim-camera needs navdeck built with the `vision` feature \
                 (cargo build --features vision; needs OpenCV: libopencv-dev libopencv-contrib-dev clang libclang-dev)"
            )
        }
    }

    /// The console on this session, starting at session time `now`.
    pub fn into_app(self, now: f64) -> App {
        App::new(self.config, self.keymap, self.link, now)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn link_choices_parse() {
        assert_eq!("sim".parse::<LinkChoice>(), Ok(LinkChoice::Sim));
        assert_eq!(
            "serial:/dev/ttyACM0@57600".parse::<LinkChoice>(),
            Ok(LinkChoice::Serial("/dev/ttyACM0@57600".into()))
        );
        assert!("serial:".parse::<LinkChoice>().is_err());
        assert!("can".parse::<LinkChoice>().unwrap_err().contains("can"));
    }
}
