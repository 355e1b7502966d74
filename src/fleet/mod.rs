//! Several robots in one console: each keeps its own console (link, pilot, log, view),
//! one is selected and takes the keys, the `:` commands and the screen, and the fleet
//! panel shows them all. Stop-all reaches every robot from any mode; a robot whose link
//! is lost is marked alone, the others drive on.

pub mod config;
pub mod panel;
pub mod recording;
pub mod recruit;
mod share;

use crate::app::fleet_view::{FleetAsk, FleetMark};
use crate::app::log::Level;
use crate::app::{App, KeyKind, LinkStatus};
use crate::control::fleet_yield::Peer;
use crate::keymap::{Action, Key};
use crate::tui::deck::Deck;
use crate::tui::theme::Theme;
use ratatui::Frame;

/// One robot of the fleet: its name in the panel and `:robot NAME`, and its console.
pub struct Member {
    pub name: String,
    pub app: App,
}

/// The robots of one console; see the module comment.
pub struct Fleet {
    members: Vec<Member>,
    selected: usize,
    /// The terminal's size in cells.
    screen: (u16, u16),
    /// Counts what changes the fleet's own part of the screen (the selection).
    changes: u64,
    /// Each robot's link status as last seen, to name a change once.
    links: Vec<LinkStatus>,
    quit: bool,
    /// Session times at which every robot was told to stop.
    stops: Vec<f64>,
    /// Robots that may join from the domain (a ROS 2 fleet).
    recruiter: Option<recruit::Recruiter>,
    /// Which twin works on which block.
    claims: crate::mission::claims::Claims,
    /// Which twin explores which ground.
    frontiers: crate::mission::frontier_claims::FrontierClaims,
    /// The fleet's own calls, into its recording (`recording.rs`).
    recorder: Option<crate::record::Recorder>,
}

impl Fleet {
    /// A fleet of `members`, the first selected. Names must differ: `:robot NAME` finds
    /// one by it.
    pub fn new(members: Vec<Member>) -> Fleet {
        assert!(!members.is_empty(), "a fleet has at least one robot");
        let links = members
            .iter()
            .map(|m| m.app.pilot().link_status().clone())
            .collect();
        let mut fleet = Fleet {
            members,
            selected: 0,
            screen: (80, 24),
            changes: 0,
            links,
            quit: false,
            stops: Vec::new(),
            recruiter: None,
            claims: Default::default(),
            frontiers: Default::default(),
            recorder: None,
        };
        let names: Vec<String> = fleet.members.iter().map(|m| m.name.clone()).collect();
        let text = format!(
            "fleet of {}: {}; ctrl-n selects the next, :robot NAME one by name, X stops all",
            names.len(),
            names.join(", ")
        );
        for m in (fleet.members.iter_mut()).filter(|_| names.len() > 1) {
            m.app.note(Level::Info, text.clone());
        }
        fleet.mark_others();
        fleet
    }

    /// The fleet's robots, the first first, for the end of a session.
    pub fn into_members(self) -> Vec<Member> {
        self.members
    }

    /// A fleet of the consoles on `sessions`, each starting at session time `now`.
    pub fn of_sessions(sessions: Vec<(String, crate::session::Session)>, now: f64) -> Fleet {
        Fleet::new(
            (sessions.into_iter())
                .map(|(name, s)| Member {
                    name,
                    app: s.into_app(now),
                })
                .collect(),
        )
    }

    pub fn members(&self) -> &[Member] {
        &self.members
    }

    pub fn members_mut(&mut self) -> &mut [Member] {
        &mut self.members
    }

    /// Session times at which every robot was told to stop (the stop-all key).
    pub fn stop_all_times(&self) -> &[f64] {
        &self.stops
    }

    pub fn selected(&self) -> usize {
        self.selected
    }

    /// The selected robot's console.
    pub fn app(&self) -> &App {
        &self.members[self.selected].app
    }

    fn app_mut(&mut self) -> &mut App {
        &mut self.members[self.selected].app
    }

    /// Selects robot `index` (from 0), saying so in its log.
    pub fn select(&mut self, index: usize) {
        if index >= self.members.len() || index == self.selected {
            return;
        }
        self.selected = index;
        self.changes += 1;
        let name = self.members[index].name.clone();
        let n = self.members.len();
        self.app_mut().note(
            Level::Info,
            format!("robot {name} ({}/{n}) selected", index + 1),
        );
        self.mark_others();
    }

    /// Stops every robot as the stop key stops one (an autonomous mode pauses), and says
    /// so in the selected robot's log.
    pub fn stop_all(&mut self) {
        self.stops.push(self.app().now());
        for m in &mut self.members {
            m.app.apply(Action::Stop);
        }
        let n = self.members.len();
        self.app_mut()
            .note(Level::Warn, format!("stop all: {n} robots told to stop"));
    }

    /// Acts on what the selected console asked of the fleet.
    fn take_ask(&mut self) {
        let Some(ask) = self.app_mut().take_fleet_ask() else {
            return;
        };
        let n = self.members.len();
        match ask {
            FleetAsk::StopAll => self.stop_all(),
            FleetAsk::Step(by) => {
                let next = (self.selected as i64 + i64::from(by)).rem_euclid(n as i64);
                self.select(next as usize);
            }
            FleetAsk::Add(ns) => self.add_robot(&ns),
            FleetAsk::Select(name) => match self.find(&name) {
                Some(i) => self.select(i),
                None => {
                    let names: Vec<&str> = self.members.iter().map(|m| m.name.as_str()).collect();
                    let text = format!(
                        ":robot {name}: no such robot; the fleet has {} (or 1..{n})",
                        names.join(", ")
                    );
                    self.app_mut().note(Level::Error, text);
                }
            },
        }
    }

    /// The robot named `name`, or numbered so from 1.
    fn find(&self, name: &str) -> Option<usize> {
        let by_name = self.members.iter().position(|m| m.name == name);
        let by_number = name
            .parse::<usize>()
            .ok()
            .filter(|k| (1..=self.members.len()).contains(k))
            .map(|k| k - 1);
        by_name.or(by_number)
    }

    /// The other robots on the selected console's map, where each believes it is.
    fn mark_others(&mut self) {
        let marks: Vec<FleetMark> = (self.members.iter().enumerate())
            .filter(|(i, _)| *i != self.selected)
            .map(|(i, m)| FleetMark {
                number: i + 1,
                name: m.name.clone(),
                pose: m.app.pilot().estimated_pose(),
            })
            .collect();
        self.app_mut().set_fleet_marks(marks);
    }

    /// Names in the selected console's log each robot whose link was lost or came back.
    fn note_links(&mut self) {
        for i in 0..self.members.len() {
            let now = self.members[i].app.pilot().link_status().clone();
            if now == self.links[i] {
                continue;
            }
            self.links[i] = now.clone();
            // A robot not yet heard from is awaited, not lost: its row says so.
            let awaited = !self.members[i].app.pilot().link_ever_up();
            if i == self.selected || awaited {
                continue;
            }
            let name = self.members[i].name.clone();
            let (level, text) = match now {
                LinkStatus::Lost(why) => (Level::Warn, format!("robot {name}: link lost ({why})")),
                LinkStatus::Back => (Level::Info, format!("robot {name}: link back")),
                LinkStatus::Ok => (Level::Info, format!("robot {name}: link up")),
            };
            self.app_mut().note(level, text);
        }
    }

    /// Tells each twin's pilot where the fleet's other twins stand, so that it gives way
    /// to them. Twins of one world share its frame; robots on real links each have
    /// their own odometry frame, which navdeck does not yet join into one map.
    fn tell_peers(&mut self) {
        let peers: Vec<Peer> = (self.members.iter().enumerate())
            .filter(|(_, m)| m.app.link().ground_truth().is_some())
            .map(|(i, m)| Peer {
                number: i + 1,
                pose: m.app.pilot().estimated_pose(),
                linear: m.app.pilot().measured().linear,
            })
            .collect();
        if peers.len() < 2 {
            return;
        }
        for peer in &peers {
            let others = peers.iter().filter(|p| p.number != peer.number).copied();
            self.members[peer.number - 1]
                .app
                .set_fleet(peer.number, others.collect());
        }
    }

    /// Rows the fleet panel takes at the bottom of a `height`-row terminal.
    fn panel_rows(&self, height: u16) -> u16 {
        panel::rows_for(self.members.len(), height)
    }
}

impl Deck for Fleet {
    fn resize(&mut self, width: u16, height: u16) {
        let now = self.app().now();
        self.record_input(crate::msgs::record::InputMsg::resize(now, width, height));
        self.screen = (width, height);
        let rest = height.saturating_sub(self.panel_rows(height));
        for m in &mut self.members {
            m.app.resize(width, rest);
        }
        self.changes += 1;
    }

    fn update(&mut self, now: f64) {
        self.record_input(crate::msgs::record::InputMsg::update(now));
        self.tell_peers();
        let explored = self.explored_layers();
        for i in 0..self.members.len() {
            // Each robot steps knowing what the others claimed before it.
            self.share_work(i);
            self.share_exploration(i, &explored);
            self.members[i].app.update(now);
        }
        if let Some(m) = self.members.iter().find(|m| m.app.should_quit()) {
            let why = format!("robot {} quit the console", m.name);
            for m in self.members.iter_mut().filter(|m| !m.app.should_quit()) {
                m.app.shutdown(&why);
            }
            self.quit = true;
        }
        self.note_links();
        self.mark_others();
        self.look_for_robots(now);
    }

    fn handle_key(&mut self, key: Key, kind: KeyKind, now: f64) {
        let event = crate::msgs::record::InputMsg::key(now, key.to_string(), kind as u8);
        self.record_input(event);
        self.app_mut().handle_key(key, kind, now);
        self.take_ask();
        if self.app().should_quit() {
            let why = format!(
                "robot {} quit the console",
                self.members[self.selected].name
            );
            for m in self.members.iter_mut().filter(|m| !m.app.should_quit()) {
                m.app.shutdown(&why);
            }
            self.quit = true;
        }
    }

    fn should_quit(&self) -> bool {
        self.quit
    }

    fn revision(&self) -> u64 {
        let apps: u64 = self.members.iter().map(|m| m.app.revision()).sum();
        apps.wrapping_add(self.changes)
    }

    fn next_deadline(&self) -> f64 {
        (self.members.iter())
            .map(|m| m.app.next_deadline())
            .fold(f64::INFINITY, f64::min)
    }

    fn shutdown(&mut self, reason: &str) {
        for m in &mut self.members {
            m.app.shutdown(reason);
        }
    }

    fn draw(&self, frame: &mut Frame, theme: Theme) {
        self.draw_in(frame, frame.area(), theme);
    }
}

impl Fleet {
    /// The selected robot's console above the fleet panel, in `area` (from the top of
    /// the frame).
    pub fn draw_in(&self, frame: &mut Frame, area: ratatui::layout::Rect, theme: Theme) {
        self.draw_showing(frame, area, theme, self.selected);
    }

    /// Robot `shown`'s console (a replay may show another than the selected one) above
    /// the fleet panel, in `area` (from the top of the frame).
    pub fn draw_showing(
        &self,
        frame: &mut Frame,
        area: ratatui::layout::Rect,
        theme: Theme,
        shown: usize,
    ) {
        let rows = self.panel_rows(area.height);
        let top = ratatui::layout::Rect::new(0, 0, area.width, area.height - rows);
        let app = &self
            .members
            .get(shown)
            .unwrap_or(&self.members[self.selected])
            .app;
        crate::tui::draw::draw_in(frame, top, app, theme);
        if rows == 0 {
            return;
        }
        let bottom = ratatui::layout::Rect::new(0, area.height - rows, area.width, rows);
        panel::render(self, theme, bottom, frame);
    }
}

#[cfg(test)]
mod tests;
