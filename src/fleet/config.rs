//! `[[fleet]]` in the config: the robots one console drives, each with its name, its
//! link, and for ROS 2 its namespace, and how it is localised.

use crate::session::{LinkChoice, LocalizeChoice};
use crate::slam::mcl::config::Estimator;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// One robot of the config's fleet.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FleetEntry {
    /// Its name in the fleet panel and for `:robot NAME`.
    pub name: String,
    /// `sim` (a twin in the fleet's one world), `ros2` or `serial:PATH[@BAUD]`.
    #[serde(default = "sim")]
    pub link: String,
    /// ROS 2: the namespace of its topics, e.g. "/tb3_0".
    #[serde(default)]
    pub namespace: Option<String>,
    /// `ekf` (default), `mcl` or `slam`, as `--estimator`.
    #[serde(default)]
    pub estimator: Option<String>,
    /// The map MCL localises on, or lidar SLAM continues, as `--map`.
    #[serde(default)]
    pub map: Option<PathBuf>,
}

fn sim() -> String {
    "sim".into()
}

impl FleetEntry {
    /// The link it names.
    pub fn link_choice(&self) -> Result<LinkChoice, String> {
        self.link.parse()
    }

    /// How it is localised.
    pub fn localize(&self) -> Result<LocalizeChoice, String> {
        let estimator = match &self.estimator {
            Some(name) => Some(name.parse::<Estimator>().map_err(|e| e.to_string())?),
            None => None,
        };
        Ok(LocalizeChoice {
            estimator,
            map: self.map.clone(),
            initial_pose: None,
        })
    }
}

/// The first problem with `entries`, as (field, value, why): a name empty or given
/// twice, a link that is not one, a namespace that is not one or on a link that is not
/// ROS 2, an estimator navdeck does not know.
pub fn problem(entries: &[FleetEntry]) -> Option<(String, String, String)> {
    for (i, e) in entries.iter().enumerate() {
        let field = |f: &str| format!("fleet[{i}].{f}");
        if e.name.trim().is_empty() || e.name.chars().any(char::is_whitespace) {
            return Some((
                field("name"),
                format!("{:?}", e.name),
                "a name is one word".into(),
            ));
        }
        if entries[..i].iter().any(|o| o.name == e.name) {
            return Some((
                field("name"),
                format!("{:?}", e.name),
                "names a robot already".into(),
            ));
        }
        let link = match e.link_choice() {
            Ok(link) => link,
            Err(why) => return Some((field("link"), format!("{:?}", e.link), why)),
        };
        if let Some(ns) = &e.namespace {
            if !matches!(link, LinkChoice::Ros2(_)) {
                let why = "a namespace is for link = \"ros2\"".to_string();
                return Some((field("namespace"), format!("{ns:?}"), why));
            }
            if let Err(why) = crate::link::ros2::config::check_namespace(ns) {
                return Some((field("namespace"), format!("{ns:?}"), why));
            }
        }
        if let Err(why) = e.localize() {
            let value = format!("{:?}", e.estimator.clone().unwrap_or_default());
            return Some((field("estimator"), value, why));
        }
    }
    None
}
