//! The command line (`:`): a typed command is an intent like a key's action, applied
//! through the same `App::apply` (helix's typable and static commands in one type).

use crate::control::config::ControllerKind;
use crate::geometry::Point2;
use crate::keymap::Action;
use crate::pilot::tag_route::TagGoal;
use crate::pilot::waypoints::{RouteAsk, Waypoint};

/// The commands that take arguments, so no key can stand for them.
#[derive(Clone, Debug, PartialEq)]
pub enum Typed {
    /// `robot NAME`: select the fleet's robot of that name or number.
    Robot(String),
    /// `robot add NS`: drive the robot under ROS 2 namespace NS too.
    AddRobot(String),
    /// `goto X Y`: plan to a point of the map frame, metres.
    GotoPoint(Point2),
    /// `goto X Y THETA_DEG`: plan to a pose, ending facing THETA (RViz's "2D Goal Pose").
    GotoPose(crate::geometry::Pose2),
    /// `goto marker ID`: plan to a landmark's approach point.
    GotoMarker(u32),
    /// `controller NAME`.
    Controller(ControllerKind),
    /// `controller` alone: say which one drives and what the others are.
    WhichController,
    /// `save NAME`: save the map as NAME.yaml + NAME.pgm in the maps folder.
    Save(String),
    /// `mission restart`: forget the paused mission and start a fresh one.
    RestartMission,
    /// `pose X Y THETA_DEG`: place the pose estimate (RViz's "2D Pose Estimate").
    SetPose(crate::geometry::Pose2),
    /// `relocalize`: MCL's global localisation afresh.
    Relocalize,
    /// `localise`: drive the move that tells MCL's hypotheses apart until it localises.
    Localise,
    /// `waypoint add X Y [THETA_DEG]` or `goto+ X Y [THETA_DEG]`: queue a waypoint.
    AddWaypoint(Waypoint),
    /// `waypoint add` alone: queue the goal cursor.
    AddCursorWaypoint,
    /// `route start|pause|skip|clear|loop N`.
    Route(RouteAsk),
    /// `route save NAME` and `route load NAME`: a route file (NAME.route.yaml in the maps
    /// folder, or a path as it is when it has a `/` or ends in `.yaml`).
    SaveRoute(String),
    LoadRoute(String),
    /// `route` or `route show`: list the waypoints in the log.
    ShowRoute,
    /// `route TASK`, `route task NAME`, `route tag ID`: route mode drives a tag map's
    /// task, or to one tag (seed 003).
    TagRoute(crate::pilot::tag_route::TagGoal),
    /// `behaviours`: the arbiter's last transitions, in the log.
    ShowBehaviours,
    /// `behaviour NAME on|off [SECONDS]`.
    SwitchBehaviour {
        behaviour: crate::pilot::behaviours::Behaviour,
        on: bool,
        seconds: Option<f64>,
    },
    /// `fault SPEC`: inject a fault into the twin, from now when SPEC has no `@START`
    /// (`camera+20`), else at that simulated time (`camera@60+20`). The spec is kept as
    /// typed: "now" is read when it is applied.
    Fault(String),
    /// `fault clear`: end every fault in force and forget those still to come.
    ClearFaults,
    /// `fault` alone: list the faults in force and those to come.
    ShowFaults,
    /// `zone …`: keepout and speed zones (app/zones.rs).
    Zone(super::zones::ZoneTyped),
}

/// Everything that changes the console's state, through one door (`App::apply`): a key's
/// action or a typed command.
#[derive(Clone, Debug, PartialEq)]
pub enum Intent {
    Action(Action),
    Typed(Typed),
}

impl From<Action> for Intent {
    fn from(action: Action) -> Self {
        Intent::Action(action)
    }
}

impl From<Typed> for Intent {
    fn from(typed: Typed) -> Self {
        Intent::Typed(typed)
    }
}

pub const USAGE: &str = "goto X Y [THETA_DEG] | goto marker ID | goto+ X Y [THETA_DEG] | waypoint add [X Y [THETA_DEG]] | route start|pause|skip|clear|loop N|save NAME|load NAME | route TASK|tag ID | controller [pid|pure_pursuit|hybrid] | clear | save [NAME] | mission restart | pose X Y THETA_DEG | relocalize | localise | fault KIND[@START][+DURATION][:PARAM]|clear | zone keepout|speed|list|delete|clear|load … | robot NAME|add NS | quit";

/// A waypoint from `X Y [THETA_DEG]` words; `what` names the command in errors.
fn waypoint(what: &str, words: &[&str]) -> Result<Waypoint, String> {
    let number = |s: &str| {
        s.trim_end_matches(',')
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite() && v.abs() <= 1.0e5)
            .ok_or_else(|| format!("{what}: `{s}` is not a number"))
    };
    match words {
        [x, y] => Ok(Waypoint {
            position: Point2::new(number(x)?, number(y)?),
            yaw: None,
        }),
        [x, y, theta] => Ok(Waypoint {
            position: Point2::new(number(x)?, number(y)?),
            yaw: Some(number(theta)?.to_radians()),
        }),
        _ => Err(format!(
            "{what} wants X Y in metres (and a heading in degrees)"
        )),
    }
}

/// `route …`.
fn route(words: &[&str]) -> Result<Intent, String> {
    let ask = match words {
        [] | ["show"] => return Ok(Typed::ShowRoute.into()),
        ["start"] => RouteAsk::Start,
        ["pause"] => RouteAsk::Pause,
        ["skip"] => RouteAsk::Skip,
        ["clear"] => RouteAsk::Clear,
        ["loop", n] => RouteAsk::Loop(
            n.parse()
                .ok()
                .filter(|n| (1..=1000).contains(n))
                .ok_or_else(|| format!("route loop: `{n}` is not a count from 1 to 1000"))?,
        ),
        ["save", name] => return Ok(Typed::SaveRoute(name.to_string()).into()),
        ["load", name] => return Ok(Typed::LoadRoute(name.to_string()).into()),
        // Route mode's (seed 003): a task of the tag map, or one tag.
        ["tag", id] => {
            let id = id
                .parse()
                .map_err(|_| format!("route tag: `{id}` is not a tag id"))?;
            return Ok(Typed::TagRoute(TagGoal::Tag(id)).into());
        }
        ["task", name] | [name] => {
            return Ok(Typed::TagRoute(TagGoal::Task(name.to_string())).into());
        }
        _ => {
            return Err(
                "route wants start, pause, skip, clear, loop N, save NAME or load NAME (waypoints), \
                 or TASK, task NAME or tag ID (route mode's tag map)"
                    .to_string(),
            );
        }
    };
    Ok(Typed::Route(ask).into())
}

/// Reads one command line, or says what is wrong with it.
pub fn parse(line: &str) -> Result<Intent, String> {
    let words: Vec<&str> = line.split_whitespace().collect();
    match words.as_slice() {
        ["goto", "marker", id] => id
            .parse()
            .map(|id| Typed::GotoMarker(id).into())
            .map_err(|_| format!("goto marker: `{id}` is not a marker ID")),
        ["goto", x, y] => {
            let coord = |s: &str| {
                s.trim_end_matches(',')
                    .parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| format!("goto: `{s}` is not a number of metres"))
            };
            Ok(Typed::GotoPoint(Point2::new(coord(x)?, coord(y)?)).into())
        }
        ["goto", x, y, theta] => crate::geometry::parse_pose_degrees(&format!("{x},{y},{theta}"))
            .map(|p| Typed::GotoPose(p).into())
            .map_err(|e| format!("goto: {e}")),
        ["goto", ..] => {
            Err("goto wants X Y in metres (and a heading in degrees), or marker ID".to_string())
        }
        ["goto+", "marker", ..] => Err(
            "goto+: waypoints are poses; goto+ X Y [THETA_DEG] (a marker is :goto marker ID)"
                .to_string(),
        ),
        ["goto+", rest @ ..] => waypoint("goto+", rest).map(|w| Typed::AddWaypoint(w).into()),
        ["waypoint", "add"] => Ok(Typed::AddCursorWaypoint.into()),
        ["waypoint", "add", rest @ ..] => {
            waypoint("waypoint add", rest).map(|w| Typed::AddWaypoint(w).into())
        }
        ["waypoint", ..] => {
            Err("waypoint wants `add` (at the cursor) or `add X Y [THETA_DEG]`".to_string())
        }
        ["route", rest @ ..] => route(rest),
        ["zone" | "zones", rest @ ..] => super::zones::parse(rest).map(Intent::Typed),
        ["controller"] => Ok(Typed::WhichController.into()),
        ["controller", name] => name
            .parse()
            .map(|kind| Typed::Controller(kind).into())
            .map_err(|e: crate::control::config::UnknownController| e.to_string()),
        ["controller", ..] => Err(
            "controller takes one name, pid, pure_pursuit or hybrid (alone: which one drives)"
                .to_string(),
        ),
        // The same as the key that clears the route.
        ["clear"] => Ok(Action::ClearRoute.into()),
        ["mission", "restart"] => Ok(Typed::RestartMission.into()),
        ["pose", x, y, theta] => crate::geometry::parse_pose_degrees(&format!("{x},{y},{theta}"))
            .map(|p| Typed::SetPose(p).into())
            .map_err(|e| format!("pose: {e}")),
        ["pose", ..] => Err("pose wants X Y (metres) and THETA (degrees)".to_string()),
        ["relocalize"] => Ok(Typed::Relocalize.into()),
        ["behaviours" | "behaviors"] => Ok(Typed::ShowBehaviours.into()),
        ["behaviour" | "behavior", rest @ ..] => behaviour(rest),
        ["localise" | "localize"] => Ok(Typed::Localise.into()),
        ["fault"] => Ok(Typed::ShowFaults.into()),
        ["fault", "clear"] => Ok(Typed::ClearFaults.into()),
        ["fault", spec] => crate::sim::FaultSpec::parse_at(spec, 0.0)
            .map(|_| Typed::Fault(spec.to_string()).into())
            .map_err(|e| e.to_string()),
        ["fault", ..] => Err(
            "fault wants one KIND[@START][+DURATION][:PARAM] (e.g. camera+20: dark for 20 s from now), or clear"
                .to_string(),
        ),
        // vim's quit: stops the robot and ends the session, as the quit key does.
        ["q" | "quit"] => Ok(Action::Quit.into()),
        ["robot", "add", ns] => crate::link::ros2::config::check_namespace(ns)
            .map(|_| Typed::AddRobot(ns.to_string()).into()),
        ["robot", name] => Ok(Typed::Robot(name.to_string()).into()),
        ["robot", ..] => Err("robot wants one NAME or number (the fleet panel lists them)".to_string()),
        ["mission", ..] => Err("mission wants `restart` (e resumes a paused mission)".to_string()),
        ["save", name] => Ok(Typed::Save(name.to_string()).into()),
        // The same as the save key: maps/saved.
        ["save"] => Ok(Action::SaveMap.into()),
        ["save", ..] => Err("save wants one NAME (letters, digits, - and _)".to_string()),
        [] => Err(format!("empty command; try {USAGE}")),
        [other, ..] => Err(format!("unknown command `{other}`; try {USAGE}")),
    }
}

/// `behaviour NAME on|off [SECONDS]`.
fn behaviour(words: &[&str]) -> Result<Intent, String> {
    use crate::pilot::behaviours::Behaviour;
    const WANTS: &str =
        "behaviour wants NAME on|off [SECONDS], e.g. `behaviour collision_monitor off 30`";
    let (name, switch, seconds) = match words {
        [name, switch] => (name, switch, None),
        [name, switch, s] => (name, switch, Some(s)),
        _ => return Err(WANTS.to_string()),
    };
    let behaviour = Behaviour::named(name).ok_or_else(|| {
        let names: Vec<&str> = Behaviour::ALL.iter().map(|b| b.name()).collect();
        format!("behaviour: unknown `{name}`; one of {}", names.join(", "))
    })?;
    let on = match *switch {
        "on" => true,
        "off" => false,
        other => return Err(format!("behaviour: `{other}` is not on or off; {WANTS}")),
    };
    let seconds = match seconds {
        None => None,
        Some(_) if on => return Err("behaviour: a time goes with off only".to_string()),
        Some(s) => match s.parse::<f64>() {
            Ok(v) if v.is_finite() && v > 0.0 => Some(v),
            _ => {
                return Err(format!(
                    "behaviour: `{s}` is not a positive number of seconds"
                ));
            }
        },
    };
    Ok(Typed::SwitchBehaviour {
        behaviour,
        on,
        seconds,
    }
    .into())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_issue_examples() {
        assert_eq!(
            parse("goto 1.20 -0.50"),
            Ok(Typed::GotoPoint(Point2::new(1.2, -0.5)).into())
        );
        assert_eq!(parse("goto marker 421"), Ok(Typed::GotoMarker(421).into()));
        let pose = crate::geometry::Pose2::new(1.5, -0.5, 90f64.to_radians());
        assert_eq!(parse("goto 1.5 -0.5 90"), Ok(Typed::GotoPose(pose).into()));
        assert!(parse("goto 1.5 -0.5 east").unwrap_err().contains("east"));
        assert_eq!(
            parse("controller pid"),
            Ok(Typed::Controller(ControllerKind::Pid).into())
        );
        assert_eq!(parse("clear"), Ok(Intent::Action(Action::ClearRoute)));
        assert_eq!(parse("controller"), Ok(Typed::WhichController.into()));
        assert_eq!(parse("save"), Ok(Intent::Action(Action::SaveMap)));
        assert_eq!(parse("mission restart"), Ok(Typed::RestartMission.into()));
        assert_eq!(
            parse("pose 1.5 -0.5 90"),
            Ok(Typed::SetPose(crate::geometry::Pose2::new(
                1.5,
                -0.5,
                std::f64::consts::FRAC_PI_2
            ))
            .into())
        );
        assert_eq!(parse("relocalize"), Ok(Typed::Relocalize.into()));
        assert_eq!(parse("behaviours"), Ok(Typed::ShowBehaviours.into()));
        use crate::pilot::behaviours::Behaviour;
        assert_eq!(
            parse("behaviour collision_monitor off 30"),
            Ok(Typed::SwitchBehaviour {
                behaviour: Behaviour::CollisionMonitor,
                on: false,
                seconds: Some(30.0)
            }
            .into())
        );
        assert!(parse("behaviour warp off").unwrap_err().contains("warp"));
        assert!(parse("behaviour teleop off -3").unwrap_err().contains("-3"));
        assert!(
            parse("behaviour teleop maybe")
                .unwrap_err()
                .contains("maybe")
        );
        assert_eq!(parse("localise"), Ok(Typed::Localise.into()));
        assert_eq!(parse("localize"), Ok(Typed::Localise.into()));
        assert_eq!(
            parse("fault camera+20"),
            Ok(Typed::Fault("camera+20".into()).into())
        );
        assert_eq!(parse("fault clear"), Ok(Typed::ClearFaults.into()));
        assert_eq!(parse("fault"), Ok(Typed::ShowFaults.into()));
        assert_eq!(parse("q"), Ok(Intent::Action(Action::Quit)));
        assert_eq!(parse("quit"), Ok(Intent::Action(Action::Quit)));
    }

    #[test]
    fn bad_input_names_the_value() {
        assert!(parse("goto 1.2 north").unwrap_err().contains("`north`"));
        assert!(parse("goto 1e400 0").unwrap_err().contains("1e400"));
        assert!(parse("fly 1 2").unwrap_err().contains("`fly`"));
        assert!(parse("controller lqr").unwrap_err().contains("lqr"));
        let e = parse("controller pid pid pid").unwrap_err();
        assert!(e.starts_with("controller takes one name"), "{e}");
        assert!(parse("pose 1 2 nan").unwrap_err().contains("nan"));
        assert!(parse("pose 1 2").unwrap_err().contains("THETA"));
        assert!(parse("route loop 0").unwrap_err().contains("`0`"));
        assert!(parse("goto+ 1 east").unwrap_err().contains("`east`"));
        let e = parse("fault cmaera+20").unwrap_err();
        assert!(e.contains("unknown sensor `cmaera`"), "{e}");
        assert!(
            parse("fault camera 20")
                .unwrap_err()
                .starts_with("fault wants")
        );
    }

    #[test]
    fn reads_waypoints_and_routes() {
        let w = Waypoint {
            position: Point2::new(1.0, 2.0),
            yaw: Some(std::f64::consts::FRAC_PI_2),
        };
        assert_eq!(parse("goto+ 1 2 90"), Ok(Typed::AddWaypoint(w).into()));
        assert_eq!(
            parse("waypoint add 1 2 90"),
            Ok(Typed::AddWaypoint(w).into())
        );
        assert_eq!(parse("waypoint add"), Ok(Typed::AddCursorWaypoint.into()));
        assert_eq!(
            parse("route loop 2"),
            Ok(Typed::Route(RouteAsk::Loop(2)).into())
        );
        assert_eq!(
            parse("route save r1"),
            Ok(Typed::SaveRoute("r1".into()).into())
        );
    }

    #[test]
    fn reads_route_modes_tasks_and_tags() {
        let task = |name: &str| Ok(Typed::TagRoute(TagGoal::Task(name.into())).into());
        assert_eq!(parse("route task1"), task("task1"));
        // `task` names a task that shares a word with the waypoint route's commands.
        assert_eq!(parse("route task start"), task("start"));
        assert_eq!(
            parse("route start"),
            Ok(Typed::Route(RouteAsk::Start).into())
        );
        assert_eq!(
            parse("route tag 205"),
            Ok(Typed::TagRoute(TagGoal::Tag(205)).into())
        );
        assert!(
            parse("route tag x")
                .unwrap_err()
                .contains("`x` is not a tag id")
        );
        assert!(parse("route a b c").unwrap_err().contains("tag ID"));
    }
}
