//! A corpus of hostile inputs run against the built binary, each as a user would meet it:
//! under a 20 s time limit and a 2 GiB address-space limit, every case must end with an
//! exit status from 1 to 99, a message naming what was wrong, no panic, and no raw
//! escape character in what reaches the terminal. A case marked `or_clean` may instead
//! succeed (exit 0), as a replay that skips what it cannot use does, if nothing it
//! prints is NaN, infinite or a null number.
//!
//! The config cases are made from navdeck's own default config: every number in it,
//! set to NaN, 1e308 and -1e308 in turn, so a field added later is covered at once.

mod arm;
mod calibration;
mod cli;
mod config;
mod files;
mod keymap;
mod map;
mod mcap_bytes;
mod recording;
mod replay_frames;
mod world;

use std::path::Path;
use std::process::Command;

/// One hostile input: the files it writes, the command line, and a text the error must
/// contain (the field, file or option at fault).
struct Case {
    kind: &'static str,
    files: Vec<(String, Vec<u8>)>,
    /// Symbolic links made in the case's folder: (name, what it points to).
    links: Vec<(String, String)>,
    args: Vec<String>,
    names: String,
    /// Exit 0 is also right, with output free of NaN, inf and null.
    may_succeed: bool,
}

fn case(kind: &'static str, args: &[&str], names: &str) -> Case {
    Case {
        kind,
        files: Vec::new(),
        links: Vec::new(),
        args: args.iter().map(|s| s.to_string()).collect(),
        names: names.to_string(),
        may_succeed: false,
    }
}

impl Case {
    fn file(mut self, name: &str, body: impl Into<Vec<u8>>) -> Case {
        self.files.push((name.to_string(), body.into()));
        self
    }

    /// A symbolic link `name` to `target` (`{dir}` standing for the case's folder).
    fn link(mut self, name: &str, target: &str) -> Case {
        self.links.push((name.to_string(), target.to_string()));
        self
    }

    /// Lets the case end with exit 0 if its output holds no NaN, inf or null number.
    fn or_clean(mut self) -> Case {
        self.may_succeed = true;
        self
    }
}

/// What running a case gave: exit status, and standard output and error.
struct Outcome {
    code: Option<i32>,
    out: String,
    err: String,
}

/// Runs `case` in its own folder under `root`, `{dir}` in its arguments standing for it.
fn run(case: &Case, root: &Path, n: usize) -> Outcome {
    let dir = root.join(format!("case-{n}"));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, body) in &case.files {
        std::fs::write(dir.join(name), body).unwrap();
    }
    for (name, target) in &case.links {
        let target = target.replace("{dir}", dir.to_str().unwrap());
        std::os::unix::fs::symlink(target, dir.join(name)).unwrap();
    }
    let args: Vec<String> = case
        .args
        .iter()
        .map(|a| a.replace("{dir}", dir.to_str().unwrap()))
        .collect();
    // The limits the bar names: 2 GiB of address space, 20 s.
    let output = Command::new("sh")
        .arg("-c")
        .arg("ulimit -v 2097152; exec timeout 20 \"$@\"")
        .arg("sh")
        .arg(env!("CARGO_BIN_EXE_navdeck"))
        .args(&args)
        .current_dir(&dir)
        .output()
        .expect("sh runs");
    Outcome {
        code: output.status.code(),
        out: String::from_utf8_lossy(&output.stdout).into_owned(),
        err: String::from_utf8_lossy(&output.stderr).into_owned(),
    }
}

#[test]
fn every_hostile_input_is_refused_cleanly_naming_what_is_wrong() {
    let root = std::env::temp_dir().join(format!("navdeck-hostile-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    let mut cases = config::cases();
    cases.extend(world::cases());
    cases.extend(map::cases());
    cases.extend(keymap::cases());
    cases.extend(cli::cases());
    cases.extend(calibration::cases());
    cases.extend(recording::cases());
    cases.extend(arm::cases());
    cases.extend(files::cases());
    cases.extend(replay_frames::cases());
    let mut counts = std::collections::BTreeMap::new();
    for c in &cases {
        *counts.entry(c.kind).or_insert(0usize) += 1;
    }
    eprintln!("hostile corpus: {} cases {counts:?}", cases.len());
    assert!(cases.len() >= 150);
    // Two at a time: the machine the suite runs on has two cores.
    let failures: Vec<String> = std::thread::scope(|s| {
        let halves: Vec<_> = [0, 1]
            .into_iter()
            .map(|half| {
                let (cases, root) = (&cases, &root);
                s.spawn(move || {
                    let mut failures = Vec::new();
                    for (n, c) in cases.iter().enumerate().filter(|(n, _)| n % 2 == half) {
                        if let Some(why) = judge(c, &run(c, root, n)) {
                            failures.push(format!("{} {:?} ({}): {why}", c.kind, c.args, c.names));
                        }
                    }
                    failures
                })
            })
            .collect();
        halves.into_iter().flat_map(|h| h.join().unwrap()).collect()
    });
    let _ = std::fs::remove_dir_all(&root);
    assert!(
        failures.is_empty(),
        "{} of {} cases failed:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}

/// Why `outcome` breaks the bar for `case`, if it does.
fn judge(case: &Case, o: &Outcome) -> Option<String> {
    let said = format!("{}{}", o.out, o.err);
    let first_line = o.err.lines().next().unwrap_or_default().to_string();
    if said.contains('\u{1b}') {
        return Some("a raw escape character reached the terminal".into());
    }
    if said.contains("panicked") {
        return Some(format!("panicked: {first_line}"));
    }
    if case.may_succeed && o.code == Some(0) {
        // The text names where: the JSON field, or the word as printed.
        return unclean_number(&o.out).map(|n| format!("exit 0 printing `{n}`"));
    }
    match o.code {
        Some(code) if (1..=99).contains(&code) => {}
        Some(124) => return Some("killed after 20 s".into()),
        other => return Some(format!("exit {other:?}: {first_line}")),
    }
    if !said.contains(&case.names) {
        return Some(format!("does not name `{}`: {first_line}", case.names));
    }
    None
}

/// The first NaN or infinite number in `out`, or, in JSON, a pose coordinate that is null
/// (serde writes a NaN as null), if there is one.
fn unclean_number(out: &str) -> Option<String> {
    if let Ok(json) = serde_json::from_str::<serde_json::Value>(out.trim()) {
        return null_figure(&json, "");
    }
    let lower = out.to_ascii_lowercase();
    ["nan", "inf"]
        .into_iter()
        .find(|word| {
            lower.match_indices(word).any(|(at, _)| {
                // A word of its own, not part of "info" or "infinite" in a sentence.
                let before = lower[..at].chars().next_back();
                let after = lower[at + word.len()..].chars().next();
                !before.is_some_and(|c| c.is_ascii_alphabetic())
                    && !after.is_some_and(|c| c.is_ascii_alphabetic())
            })
        })
        .map(str::to_string)
}

/// The path of the first null pose coordinate under `value` (at `path`). Other nulls are
/// "none yet" (no path followed, no kidnap, no truth to score), as they should say.
fn null_figure(value: &serde_json::Value, path: &str) -> Option<String> {
    use serde_json::Value;
    let figure = |key: &str| {
        key.ends_with("pose") || matches!(key, "x" | "y" | "theta") && path.contains("pose")
    };
    match value {
        Value::Object(map) => map.iter().find_map(|(key, v)| {
            let here = format!("{path}.{key}");
            if v.is_null() && figure(key) {
                return Some(format!("{here} = null"));
            }
            null_figure(v, &here)
        }),
        Value::Array(items) => items
            .iter()
            .enumerate()
            .find_map(|(k, v)| null_figure(v, &format!("{path}[{k}]"))),
        _ => None,
    }
}
