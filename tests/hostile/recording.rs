//! Recordings for `navdeck replay`: the MCAP container.

use super::{Case, case};

/// Recordings for `navdeck replay`: not MCAP, empty, endless, a folder, and two files the
/// fuzzer made whose chunks and records claim sizes they do not have.
pub fn cases() -> Vec<Case> {
    let replay = |names: &str, body: Vec<u8>| {
        case("recording", &["replay", "r.mcap", "--headless"], names).file("r.mcap", body)
    };
    let inputs = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/hostile_inputs/");
    let mut out = vec![
        replay(
            "not an MCAP file",
            b"\x1b]2;owned\x07 not a recording".to_vec(),
        ),
        replay("not an MCAP file", Vec::new()),
        replay("offset 8", b"\x89MCAP0\r\n".to_vec()),
        replay(
            "offset 8",
            [
                b"\x89MCAP0\r\n".as_slice(),
                &[6, 255, 255, 255, 255, 255, 255, 255, 127],
            ]
            .concat(),
        ),
        case(
            "recording",
            &["replay", "/dev/zero", "--headless"],
            "/dev/zero",
        ),
        case(
            "recording",
            &["replay", "{dir}", "--headless"],
            "regular file",
        ),
        case(
            "recording",
            &["replay", "missing.mcap", "--headless"],
            "missing.mcap",
        ),
    ];
    for name in ["recording_chunk_lies.mcap", "recording_record_lies.mcap"] {
        let body = std::fs::read(format!("{inputs}{name}")).unwrap();
        out.push(replay("offset", body));
    }
    out
}
