//! Robots that appear on a ROS 2 fleet's domain: the console names each new one once in
//! the log, and `:robot add NS` makes it one of the fleet.

use super::{Fleet, Member};
use crate::app::log::Level;
use crate::tui::deck::Deck;

/// How often the console looks at discovery for new robots, seconds.
const LOOK_EVERY: f64 = 2.0;

/// Opens the console of the robot under a namespace, at a session time.
pub type Enlist = Box<dyn FnMut(&str, f64) -> anyhow::Result<Member>>;

/// What discovery shows and how a robot found there joins.
pub struct Recruiter {
    /// The namespaces of the robots discovery shows now.
    pub seen: Box<dyn FnMut() -> Vec<String>>,
    /// A robot's console for the namespace, with its name.
    pub add: Enlist,
    /// The namespaces of the fleet's robots and of those already named in the log.
    pub known: Vec<String>,
    /// Session time discovery was last looked at.
    pub looked_at: f64,
}

impl Fleet {
    /// Offers the robots `recruiter` finds as they appear.
    pub fn set_recruiter(&mut self, recruiter: Recruiter) {
        self.recruiter = Some(recruiter);
    }

    /// Names each robot discovery shows that is not in the fleet, once.
    pub(super) fn look_for_robots(&mut self, now: f64) {
        let Some(r) = self.recruiter.as_mut() else {
            return;
        };
        if now - r.looked_at < LOOK_EVERY {
            return;
        }
        r.looked_at = now;
        let new: Vec<String> = ((r.seen)().into_iter())
            .filter(|ns| !r.known.contains(ns))
            .collect();
        r.known.extend(new.iter().cloned());
        for ns in new {
            let text = format!("robot {ns} appeared on the domain: :robot add {ns} drives it");
            self.app_mut().note(Level::Info, text);
        }
    }

    /// `:robot add NS`: the robot under namespace `ns` joins the fleet.
    pub(super) fn add_robot(&mut self, ns: &str) {
        let now = self.app().now();
        let added = match self.recruiter.as_mut() {
            None => Err(anyhow::anyhow!("robots join only a ROS 2 fleet")),
            Some(r) => (r.add)(ns, now),
        };
        match added {
            Ok(member) => {
                if let Some(r) = self.recruiter.as_mut()
                    && !r.known.iter().any(|k| k == ns)
                {
                    r.known.push(ns.to_string());
                }
                let name = member.name.clone();
                self.links.push(member.app.pilot().link_status().clone());
                self.members.push(member);
                let (w, h) = self.screen;
                self.resize(w, h);
                let n = self.members.len();
                self.app_mut()
                    .note(Level::Info, format!("robot {name} joined: {n} robots"));
                self.note_unrecorded(&name);
            }
            Err(why) => {
                let text = format!(":robot add {ns}: {why:#}");
                self.app_mut().note(Level::Error, text);
            }
        }
    }
}
