//! Recordings for `navdeck replay`: the MCAP container.

use super::mcap_bytes::{
    attachment, channel, chunk, end, message, record, schema, start, zstd_chunk,
};
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
    out.extend(bombs(&replay));
    out
}

/// Recordings that would take more memory or time than a machine has: chunks that add
/// up to gigabytes, names of 64 kB on 40,000 messages, and chunks and attachments whose
/// headers lie.
fn bombs(replay: &dyn Fn(&str, Vec<u8>) -> Case) -> Vec<Case> {
    // 255 private records of 1 MiB: a chunk just under the 256 MiB one chunk may hold.
    let filler: Vec<u8> = (0..255).flat_map(|_| record(0x80, &[0; 1 << 20])).collect();
    let filler_chunk = zstd_chunk(&filler);
    // 4,000 messages of 64 kB on one channel: 250 MiB a chunk.
    let messages: Vec<u8> = (0..4000u64)
        .flat_map(|k| message(1, k * 1_000_000, &[0; 1 << 16]))
        .collect();
    let message_chunk = zstd_chunk(&messages);
    let twelve = |c: &[u8], head: &[u8]| [start(), head.to_vec(), c.repeat(12), end()].concat();
    let announced = [schema(1, b"std_msgs/String"), channel(1, 1, b"/chatter")].concat();
    let long = vec![b'n'; 64 << 10];
    let long_names = [
        start(),
        schema(1, &long),
        channel(1, 1, &long),
        (0..40_000u64).flat_map(|k| message(1, k, &[])).collect(),
        end(),
    ]
    .concat();
    let small = record(0x80, b"hello").repeat(5);
    let packed = zstd::encode_all(small.as_slice(), 3).unwrap();
    let claims = |claimed: u64, compression: &[u8]| {
        [start(), chunk(&packed, claimed, compression), end()].concat()
    };
    vec![
        replay("1024 MiB unpacked", twelve(&filler_chunk, &[])),
        replay("512 MiB", twelve(&message_chunk, &announced)),
        replay("nothing to replay", long_names),
        replay("more than the 4 bytes", claims(4, b"zstd")),
        replay("70 bytes, not the 7000", claims(7000, b"zstd")),
        replay("256 MiB", claims(300 << 20, b"zstd")),
        replay("256 MiB", claims(u64::MAX, b"zstd")),
        replay("\"brotli\"", claims(small.len() as u64, b"brotli")),
        replay(
            "CRC does not match",
            [start(), attachment(b"map.yaml", b"image: x", 1), end()].concat(),
        ),
    ]
}
