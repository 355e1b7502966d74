//! Config files: every number of the default config set to NaN and ±1e308, and files too
//! deep, too long or not text.

use super::{Case, case};

/// Every number of the default config as (table, key, array index).
fn numeric_fields() -> Vec<(String, String, Option<usize>)> {
    let text = toml::to_string(&navdeck::config::Config::default()).unwrap();
    let root: toml::Table = text.parse().unwrap();
    let mut out = Vec::new();
    fn walk(table: &toml::Table, path: &str, out: &mut Vec<(String, String, Option<usize>)>) {
        for (key, value) in table {
            match value {
                toml::Value::Table(t) => {
                    let sub = if path.is_empty() {
                        key.clone()
                    } else {
                        format!("{path}.{key}")
                    };
                    walk(t, &sub, out);
                }
                toml::Value::Integer(_) | toml::Value::Float(_) => {
                    out.push((path.to_string(), key.clone(), None));
                }
                toml::Value::Array(items)
                    if !items.is_empty() && items.iter().all(|v| v.is_float()) =>
                {
                    out.push((path.to_string(), key.clone(), Some(0)));
                }
                _ => {}
            }
        }
    }
    walk(&root, "", &mut out);
    out
}

pub fn cases() -> Vec<Case> {
    let plan = [
        "plan", "--config", "bad.toml", "--from", "0,0", "--to", "0.2,0",
    ];
    let deep =
        |open: &str, close: &str| format!("x = {}1{}\n", open.repeat(50_000), close.repeat(50_000));
    let mut cases = vec![
        case("config", &plan, "recursion").file("bad.toml", deep("[", "]")),
        case("config", &plan, "recursion").file("bad.toml", deep("{a = ", "}")),
        case("config", &plan, "bad.toml").file("bad.toml", vec![0xff, 0xfe, 0x00]),
        case("config", &plan, "limit").file("bad.toml", "#".repeat(2 << 20)),
        case(
            "config",
            &[
                "plan",
                "--config",
                "/dev/urandom",
                "--from",
                "0,0",
                "--to",
                "1,0",
            ],
            "regular file",
        ),
    ];
    for (table, key, index) in numeric_fields() {
        for value in ["nan", "1e308", "-1e308"] {
            let setting = match index {
                None => format!("{key} = {value}"),
                Some(_) => format!("{key} = [{value}, 0.0, 0.0]"),
            };
            let body = format!("[{table}]\n{setting}\n");
            cases.push(
                case(
                    "config",
                    &[
                        "plan", "--config", "bad.toml", "--from", "0,0", "--to", "0.2,0",
                    ],
                    &key,
                )
                .file("bad.toml", body),
            );
        }
    }
    cases
}
