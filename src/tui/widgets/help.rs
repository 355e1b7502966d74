//! The help overlay: the active mode's bindings, generated from the keymap, and a legend.

use crate::app::App;
use crate::keymap::action::{Handler, Route};
use crate::keymap::{Action, Key, KeyCode};
use crate::pilot::mode::Mode;
use crate::tui::theme::Theme;
use ratatui::text::{Line, Span};

/// Columns of a help entry: keys in 9 (or more, for a family), then the description.
pub const ENTRY_WIDTH: usize = 36;
const KEY_WIDTH: usize = 9;

/// Actions the help shows as one entry when every one of them is bound: their keys in
/// this order, one description.
const FAMILIES: [(&[Action], &str); 13] = [
    (
        &[
            Action::Forward,
            Action::Backward,
            Action::TurnLeft,
            Action::TurnRight,
        ],
        "drive, while held",
    ),
    (
        &[
            Action::ForwardLeft,
            Action::ForwardRight,
            Action::BackwardLeft,
            Action::BackwardRight,
        ],
        "drive and turn, while held",
    ),
    (&[Action::SpeedUp, Action::SpeedDown], "all speeds +/-10 %"),
    (
        &[Action::LinearUp, Action::LinearDown],
        "linear speed +/-10 %",
    ),
    (
        &[Action::AngularUp, Action::AngularDown],
        "turn rate +/-10 %",
    ),
    (&[Action::ZoomIn, Action::ZoomOut], "zoom in / out"),
    (
        &[Action::ToggleScan, Action::ToggleTrail, Action::ToggleGraph],
        "scan, trail, pose graph",
    ),
    (
        &[
            Action::PanLeft,
            Action::PanRight,
            Action::PanUp,
            Action::PanDown,
        ],
        "pan the map",
    ),
    (
        &[Action::LogOlder, Action::LogNewer],
        "log: page back / forward",
    ),
    (
        &[
            Action::CursorLeft,
            Action::CursorRight,
            Action::CursorUp,
            Action::CursorDown,
        ],
        "move the goal cursor",
    ),
    (
        &[
            Action::ArmForward,
            Action::ArmBack,
            Action::ArmLeft,
            Action::ArmRight,
        ],
        "move the tool, while held",
    ),
    (
        &[
            Action::ArmUp,
            Action::ArmDown,
            Action::ArmPitchUp,
            Action::ArmPitchDown,
        ],
        "tool up / down, pitch",
    ),
    (
        &[Action::ArmHome, Action::ArmReady, Action::ArmStow],
        "arm home, ready, stow",
    ),
];

/// A key as the help writes it: arrows and page keys as their symbols, else its name.
fn short(key: &Key) -> String {
    let plain = !key.ctrl && !key.alt;
    match (plain, key.code) {
        (true, KeyCode::Left) => "←".into(),
        (true, KeyCode::Right) => "→".into(),
        (true, KeyCode::Up) => "↑".into(),
        (true, KeyCode::Down) => "↓".into(),
        (true, KeyCode::PageUp) => "PgUp".into(),
        (false, KeyCode::Left | KeyCode::Right | KeyCode::Up | KeyCode::Down) if !key.alt => {
            let plain = Key {
                ctrl: false,
                ..*key
            };
            format!("^{}", short(&plain))
        }
        (true, KeyCode::PageDown) => "PgDn".into(),
        _ => key.to_string(),
    }
}

/// The help's entries for the active mode, as (keys, description), in `Action::ALL`
/// order; a family whose keys and description fit in one entry is shown as one.
pub fn entry_texts(app: &App) -> Vec<(String, String)> {
    let mode = app.pilot().mode();
    let bindings = app.keymap().bindings(mode);
    let keys_of = |action: Action| {
        bindings
            .iter()
            .find(|(a, _)| *a == action)
            .map(|(_, keys)| keys.iter().map(short).collect::<Vec<_>>().join(" "))
    };
    let mut entries = Vec::new();
    let mut done: Vec<Action> = Vec::new();
    // The fleet's keys are listed only in a fleet.
    let alone = app.fleet_marks().is_empty();
    for (action, keys) in &bindings {
        let for_fleet = matches!(action.route(), Route::Console(Handler::Fleet(_)));
        if done.contains(action) || (alone && for_fleet) {
            continue;
        }
        let family = FAMILIES
            .iter()
            .find(|(members, _)| members.contains(action));
        if let Some((members, text)) = family {
            let text = family_text(members, text, mode);
            let keys: Option<Vec<String>> = members.iter().map(|&m| keys_of(m)).collect();
            if let Some(keys) = keys {
                let keys = keys.join(" ");
                let width = keys.chars().count().max(KEY_WIDTH - 1) + 1 + text.chars().count();
                if width <= ENTRY_WIDTH {
                    done.extend(members.iter());
                    entries.push((keys, text.to_string()));
                    continue;
                }
            }
        }
        let names: Vec<String> = keys.iter().map(short).collect();
        entries.push((names.join(" "), action.description_in(mode).to_string()));
    }
    entries
}

/// A family's description in `mode`, where its keys mean something else there: the
/// speed keys jog the arm in gripper mode.
fn family_text(members: &[Action], text: &'static str, mode: Mode) -> &'static str {
    match (mode, members.first()) {
        (Mode::Gripper, Some(Action::SpeedUp | Action::LinearUp | Action::AngularUp)) => {
            "arm jog speed +/-10 %"
        }
        _ => text,
    }
}

/// The keys that quit in the active mode, as the title and help write them (a plain
/// key first), or the command when no key quits.
pub fn quit_keys(app: &App) -> String {
    let bindings = app.keymap().bindings(app.pilot().mode());
    // `bindings` lists a plain key before ctrl- and alt- ones.
    let quit = bindings.iter().find(|(a, _)| *a == Action::Quit);
    quit.and_then(|(_, keys)| keys.first())
        .map_or_else(|| ":quit".to_string(), short)
}

/// Lines of `key(s)  description`, one per entry.
pub fn entries(app: &App, theme: Theme) -> Vec<Line<'static>> {
    entry_texts(app)
        .into_iter()
        .map(|(keys, text)| {
            Line::from(vec![
                Span::styled(format!("{keys:<w$} ", w = KEY_WIDTH - 1), theme.title()),
                Span::styled(text, theme.value()),
            ])
        })
        .collect()
}

/// What the map's glyphs mean.
pub const LEGEND: &str = "Map: @ robot (% its footprint, zoomed in)  o true pose  + 95% ellipse  \
     # wall  : near a wall  . free  * boundary  x obstacle  R/B gate  r/b block  \
     ' lidar hit  · trail  • path  G goal  X goal cursor  ? frontier  ! exploring to  \
     ░▒▓ MCL particles";

/// How driving by keys works, for users of teleop_twist_keyboard and the like, where a
/// key press sets a speed that holds until the next key.
pub fn driving(app: &App) -> String {
    let bindings = app.keymap().bindings(app.pilot().mode());
    let stop = bindings
        .iter()
        .find(|(a, _)| *a == Action::Stop)
        .and_then(|(_, keys)| keys.first())
        .map_or_else(|| ":clear".to_string(), short);
    format!(
        "Driving: the robot moves only while a drive key is held; let go, or no key repeat \
         for {:.1} s, and it stops (the deadman). {stop} stops it here and pauses \
         autonomy; space is the emergency stop, and only space again releases it.",
        app.config().teleop.deadman_timeout
    )
}
