//! A fleet in one console: the keys drive the selected robot, stop-all reaches every
//! robot from any mode, `:robot` selects by name or number, a lost link marks one robot,
//! and the twins see and stop for each other.

use crate::common::*;
use navdeck::app::KeyKind;
use navdeck::fleet::{Fleet, Member};
use navdeck::link::{Command, LinkError, RobotLink, SensorFrame};
use navdeck::pilot::mode::Mode;
use navdeck::session::{SessionSpec, fleet};
use navdeck::tui::events::{Event, ManualClock, ScriptedEvents, Step};
use navdeck::tui::run::{RunStats, run};
use navdeck::tui::theme::Theme;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use std::sync::atomic::AtomicUsize;

/// The whole log of `app`, a line each.
fn log_of(app: &navdeck::app::App) -> String {
    let lines: Vec<&str> = app.log_book().iter().map(|e| e.text.as_str()).collect();
    lines.join("\n")
}

/// `n` twins in the built-in arena, robot 1 selected.
fn twins(n: usize) -> Fleet {
    let members = fleet::twins(&SessionSpec::twin(None), n).expect("a fleet of twins");
    Fleet::of_sessions(members, 0.0)
}

fn named(name: &str) -> Step {
    Step::Event(Event::Key(key(name), KeyKind::Press))
}

fn typed(line: &str) -> Vec<Step> {
    let mut steps = vec![press(':')];
    steps.extend(line.chars().map(press));
    steps.push(named("enter"));
    steps
}

/// Runs the real loop on `fleet` in a `w` x `h` test terminal through `steps`.
/// The clock carries on from `clock`'s time, so several plays make one session.
fn play_on(
    clock: &ManualClock,
    fleet: &mut Fleet,
    w: u16,
    h: u16,
    steps: Vec<Step>,
) -> Terminal<TestBackend> {
    let mut terminal = Terminal::new(TestBackend::new(w, h)).unwrap();
    let clock = clock.clone();
    let mut events = ScriptedEvents::new(clock.clone(), steps);
    let signal = AtomicUsize::new(0);
    let mut stats = RunStats::default();
    let theme = Theme { color: false };
    run(
        &mut terminal,
        fleet,
        &mut events,
        &clock,
        &signal,
        theme,
        &mut stats,
    )
    .unwrap();
    terminal
}

fn play(fleet: &mut Fleet, w: u16, h: u16, steps: Vec<Step>) -> Terminal<TestBackend> {
    play_on(&ManualClock::default(), fleet, w, h, steps)
}

fn truth(fleet: &Fleet, i: usize) -> navdeck::geometry::Pose2 {
    fleet.members()[i].app.true_pose().unwrap()
}

#[test]
fn the_drive_keys_move_the_selected_robot_only() {
    let mut fleet = twins(3);
    let starts: Vec<_> = (0..3).map(|i| truth(&fleet, i)).collect();
    let mut steps = hold('a', 1.0);
    steps.push(named("ctrl-n"));
    steps.extend(hold('d', 1.0));
    steps.push(Step::Wait(1.0));
    play(&mut fleet, 100, 32, steps);
    let turned = |i: usize| truth(&fleet, i).theta - starts[i].theta;
    assert!(turned(0) > 0.3, "robot 1 turned left {}", turned(0));
    assert!(turned(1) < -0.3, "robot 2 turned right {}", turned(1));
    assert_eq!(truth(&fleet, 2), starts[2], "robot 3 was never driven");
    assert_eq!(fleet.selected(), 1);
}

#[test]
fn stop_all_stops_every_robot_whatever_its_mode() {
    // Robot 1 explores, robot 2 follows a path, robot 3 turns on its key.
    let mut fleet = twins(3);
    let mut steps = vec![press('e'), Step::Wait(2.0), named("ctrl-n")];
    steps.extend(typed("goto 0.9 0.6"));
    steps.push(press('p'));
    steps.extend([Step::Wait(2.0), named("ctrl-n")]);
    steps.extend(hold('a', 0.5));
    steps.push(press('X'));
    steps.push(Step::Wait(0.1));
    // Robot 2 follows its path until the key: the same session without it ends on the way.
    let mut before = twins(3);
    play(&mut before, 100, 32, steps[..steps.len() - 2].to_vec());
    let log = log_of(&before.members()[1].app);
    assert!(
        log.contains("path to (") && !log.contains("no path"),
        "{log}"
    );
    assert!(!log.contains("arrived"), "{log}");
    play(&mut fleet, 100, 32, steps);
    for m in fleet.members() {
        let p = m.app.pilot();
        assert!(
            p.commanded().is_zero(),
            "{} still commanded {:?}",
            m.name,
            p.commanded()
        );
        assert_ne!(p.mode(), Mode::Exploration, "{} still explores", m.name);
        assert!(!p.is_busy(), "{} still busy", m.name);
    }
    let log = log_of(&fleet.members()[2].app);
    assert!(log.contains("stop all: 3 robots told to stop"), "{log}");
}

#[test]
fn robots_are_selected_by_name_or_number_and_an_unknown_name_is_named() {
    let mut fleet = twins(3);
    let clock = ManualClock::default();
    let mut steps = typed("robot robot3");
    play_on(&clock, &mut fleet, 100, 32, steps);
    assert_eq!(fleet.selected(), 2);
    steps = typed("robot 2");
    play_on(&clock, &mut fleet, 100, 32, steps);
    assert_eq!(fleet.selected(), 1);
    steps = typed("robot nobody");
    steps.push(named("ctrl-p"));
    steps.push(named("ctrl-p"));
    play_on(&clock, &mut fleet, 100, 32, steps);
    let log = log_of(&fleet.members()[1].app);
    assert!(
        log.contains(":robot nobody: no such robot; the fleet has robot1, robot2, robot3"),
        "{log}"
    );
    // Back from robot 2 past robot 1 to the last.
    assert_eq!(fleet.selected(), 2);
}

/// A robot that answers until session time `until`, then is lost.
struct AnswersUntil {
    until: f64,
}

impl RobotLink for AnswersUntil {
    fn label(&self) -> String {
        "robot-b".into()
    }
    fn send(&mut self, _: &Command) -> Result<(), LinkError> {
        Ok(())
    }
    fn poll(&mut self, now: f64) -> Result<SensorFrame, LinkError> {
        match now < self.until {
            true => Ok(SensorFrame {
                stamp: now,
                ..Default::default()
            }),
            false => Err(LinkError::Lost("no odometry for 1.0 s".into())),
        }
    }
    fn stop(&mut self) {}
}

#[test]
fn a_lost_link_marks_that_robot_only_and_the_others_drive_on() {
    let lost = navdeck::app::App::new(
        navdeck::config::Config::default(),
        navdeck::keymap::Keymap::default_map(),
        Box::new(AnswersUntil { until: 0.5 }),
        0.0,
    );
    let mut fleet = Fleet::new(vec![
        Member {
            name: "twin".into(),
            app: default_app(),
        },
        Member {
            name: "b".into(),
            app: lost,
        },
    ]);
    let start = truth(&fleet, 0);
    let mut steps = vec![Step::Wait(0.6)];
    steps.extend(hold('w', 1.5));
    let terminal = play(&mut fleet, 110, 30, steps);
    let shown = screen(&terminal);
    let row = |name: &str| {
        shown
            .lines()
            .find(|l| l.contains(&format!(" {name} ")) && l.contains("°"))
            .unwrap_or_else(|| panic!("no row for {name} in\n{shown}"))
            .to_string()
    };
    assert!(row("b").contains("LOST"), "{}", row("b"));
    assert!(row("twin").contains(" ok "), "{}", row("twin"));
    let driven = truth(&fleet, 0).position().distance(start.position());
    assert!(driven > 0.1, "the twin drove {driven} m");
    let log = log_of(&fleet.members()[0].app);
    assert!(log.contains("robot b: link lost"), "{log}");
}

#[test]
fn a_robot_driven_at_another_is_stopped_short_of_it_by_what_its_lidar_sees() {
    let mut fleet = twins(2);
    // Robot 2 starts behind robot 1, facing it.
    let (a, b) = (truth(&fleet, 0), truth(&fleet, 1));
    assert!(b.x < a.x && (a.y - b.y).abs() < 1e-9, "{a:?} {b:?}");
    let mut steps = vec![named("ctrl-n")];
    steps.extend(hold('w', 6.0));
    play(&mut fleet, 100, 32, steps);
    let gap = truth(&fleet, 0)
        .position()
        .distance(truth(&fleet, 1).position());
    let twin = fleet.members()[1].app.link().ground_truth().unwrap();
    assert_eq!((twin.robot_hits(), twin.collisions()), (0, 0), "gap {gap}");
    assert!(gap < 0.3, "robot 2 did not close in: gap {gap}");
}

#[test]
fn fleet_screen_100x32() {
    let mut fleet = twins(3);
    let mut steps = hold('w', 1.0);
    steps.push(named("ctrl-n"));
    steps.extend(hold('a', 0.5));
    steps.push(Step::Wait(0.6));
    let terminal = play(&mut fleet, 100, 32, steps);
    insta::assert_snapshot!(screen(&terminal));
}

#[test]
fn the_fleet_keys_alone_stop_the_one_robot_or_say_there_is_no_other() {
    let mut steps = hold('w', 0.5);
    steps.push(press('X'));
    steps.push(named("ctrl-n"));
    steps.push(Step::Wait(0.1));
    let done = run_script(default_app(), 80, 24, steps);
    assert!(done.app.pilot().commanded().is_zero());
    let log = log_of(&done.app);
    assert!(log.contains("one robot in this console"), "{log}");
}

#[test]
fn the_help_lists_the_fleet_keys_in_a_fleet() {
    let mut fleet = twins(2);
    let shown = screen(&play(
        &mut fleet,
        120,
        40,
        vec![press('?'), Step::Wait(0.1)],
    ));
    assert!(shown.contains("stop every robot (any mode)"), "{shown}");
    assert!(shown.contains("select the next robot"), "{shown}");
}

#[test]
fn a_config_fleet_names_its_robots_and_localises_each_its_own_way() {
    let config = navdeck::config::Config::parse(
        "[[fleet]]\nname = \"scout\"\n\n[[fleet]]\nname = \"mapper\"\nestimator = \"slam\"\n",
        std::path::Path::new("fleet.toml"),
    )
    .unwrap();
    let members = fleet::from_entries(&SessionSpec::twin(None), &config.fleet, None, None).unwrap();
    let mut fleet = Fleet::of_sessions(members, 0.0);
    play(&mut fleet, 100, 32, hold('w', 1.0));
    let [scout, mapper] = fleet.members() else {
        panic!("two robots");
    };
    assert_eq!(
        (scout.name.as_str(), mapper.name.as_str()),
        ("scout", "mapper")
    );
    assert!(scout.app.pilot().lidar_slam().is_none());
    assert!(
        mapper.app.pilot().lidar_slam().is_some(),
        "mapper maps by lidar"
    );
    // One world: the second twin stands beside the first.
    let gap = truth(&fleet, 0)
        .position()
        .distance(truth(&fleet, 1).position());
    assert!(gap < 0.5, "{gap}");
}

#[test]
fn twins_meeting_head_on_give_way_by_number_and_never_touch() {
    let mut fleet = twins(2);
    let (one, two) = (truth(&fleet, 0), truth(&fleet, 1));
    assert!(
        two.x < one.x,
        "robot 2 starts behind robot 1: {one:?} {two:?}"
    );
    // Robot 1 turns back west past robot 2; robot 2 drives east past robot 1.
    let mut steps = typed("goto -1.7 -1.5");
    steps.push(press('p'));
    steps.push(named("ctrl-n"));
    steps.extend(typed("goto -0.4 -1.5"));
    steps.push(press('p'));
    steps.push(Step::Wait(40.0));
    play(&mut fleet, 100, 32, steps);
    let hits: Vec<u32> = (fleet.members().iter())
        .map(|m| m.app.link().ground_truth().unwrap().robot_hits())
        .collect();
    assert_eq!(hits, [0, 0]);
    let log = log_of(&fleet.members()[1].app);
    assert!(log.contains("giving way to robot 1"), "{log}");
    assert!(!log_of(&fleet.members()[0].app).contains("giving way"));
    for (i, goal) in [(0, -1.7), (1, -0.4)] {
        let x = truth(&fleet, i).x;
        assert!((x - goal).abs() < 0.1, "robot {} ended at x = {x}", i + 1);
    }
}

#[test]
fn a_robot_that_appears_is_offered_once_and_joins_when_added() {
    use navdeck::fleet::recruit::Recruiter;
    let mut fleet = twins(2);
    fleet.set_recruiter(Recruiter {
        seen: Box::new(|| vec!["/tb3_0".into(), "/tb3_9".into()]),
        add: Box::new(|ns: &str, now: f64| {
            let mut spares = fleet::twins(&SessionSpec::twin(None), 1)?;
            let (_, session) = spares.remove(0);
            Ok(Member {
                name: ns.trim_start_matches('/').into(),
                app: session.into_app(now),
            })
        }),
        known: vec!["/tb3_0".into()],
        looked_at: f64::NEG_INFINITY,
    });
    let mut steps = vec![Step::Wait(5.0)];
    steps.extend(typed("robot add /tb3_9"));
    steps.extend(typed("robot tb3_9"));
    play(&mut fleet, 100, 32, steps);
    let log = log_of(&fleet.members()[0].app);
    let offer = "robot /tb3_9 appeared on the domain: :robot add /tb3_9 drives it";
    assert_eq!(log.matches(offer).count(), 1, "{log}");
    assert!(!log.contains("robot /tb3_0 appeared"), "{log}");
    assert!(log.contains("robot tb3_9 joined: 3 robots"), "{log}");
    assert_eq!(fleet.members().len(), 3);
    assert_eq!(fleet.selected(), 2);
}

#[test]
fn a_robot_added_in_the_console_writes_a_log_file_of_its_own() {
    use navdeck::console::{ConsoleOptions, prepared};
    use navdeck::fleet::recruit::Recruiter;
    use std::cell::RefCell;
    use std::rc::Rc;
    let dir = crate::common::scratch::scratch("added-log");
    let logs = Rc::new(RefCell::new(Vec::new()));
    let options = ConsoleOptions {
        maps_dir: Some(dir.join("maps")),
        log_dir: None,
        braille: false,
        record: None,
    };
    let stopwatch: std::sync::Arc<dyn navdeck::clock::Clock> =
        std::sync::Arc::new(navdeck::tui::events::ManualClock::default());
    let add = Box::new(|ns: &str, now: f64| {
        let (_, session) = fleet::twins(&SessionSpec::twin(None), 1)?.remove(0);
        Ok(Member {
            name: ns.trim_start_matches('/').into(),
            app: session.into_app(now),
        })
    });
    let mut fleet = twins(2);
    fleet.set_recruiter(Recruiter {
        seen: Box::new(Vec::new),
        add: prepared(add, &options, stopwatch, dir.clone(), logs.clone()),
        known: Vec::new(),
        looked_at: f64::NEG_INFINITY,
    });
    let mut steps = typed("robot add /tb3_9");
    steps.extend(typed("robot tb3_9"));
    steps.push(Step::Wait(1.0));
    play(&mut fleet, 100, 32, steps);
    assert_eq!(fleet.members().len(), 3);
    let files = logs.borrow().clone();
    assert_eq!(files.len(), 1, "{files:?}");
    let name = files[0].file_name().unwrap().to_string_lossy().into_owned();
    assert!(
        name.ends_with("-tb3_9.log") && files[0].starts_with(&dir),
        "{name}"
    );
    drop(fleet);
    let text = std::fs::read_to_string(&files[0]).unwrap();
    assert!(
        !text.trim().is_empty(),
        "the added robot's log file is empty"
    );
}

#[test]
fn two_twins_deliver_a_generated_worlds_blocks_sooner_than_one_and_touch_nothing() {
    use navdeck::sim::generate::{GenerateOptions, generate};
    let world = generate(&GenerateOptions {
        seed: 1,
        ..GenerateOptions::default()
    })
    .unwrap();
    let spec = SessionSpec {
        seed: 1,
        ..SessionSpec::twin(None)
    };
    let pair = fleet::twins_in(&spec, world.clone(), 2).unwrap();
    let fleet_run = navdeck::runners::fleet_mission::run(pair, 1, 1200.0);
    assert!(fleet_run.success(), "{fleet_run:?}");
    let (config, link) = navdeck::session::Session::load_with_world(&spec, world)
        .unwrap()
        .into_link();
    let alone = navdeck::runners::mission::run(&config, link, None, 1, 1200.0, false);
    assert_eq!(alone.true_delivered, Some(fleet_run.total));
    assert!(
        fleet_run.sim_time < alone.sim_time,
        "two robots {:.1} s, one {:.1} s",
        fleet_run.sim_time,
        alone.sim_time
    );
}
