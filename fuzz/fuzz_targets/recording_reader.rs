//! Fuzzes the recording reader behind `navdeck replay`: the input is an MCAP file. Any
//! input must read up to its first damage and decode for replay without a crash or a
//! huge allocation; damage must be named with its byte offset and reach the replay's
//! problems, and the messages read must come out in log-time order.
#![no_main]

use libfuzzer_sys::fuzz_target;
use navdeck::record::reader;
use navdeck::record::recorded::Recorded;

fuzz_target!(|data: &[u8]| {
    let raw = reader::read(data);
    if let Some(damage) = &raw.damage {
        assert!(
            damage.starts_with("offset "),
            "damage without its offset: {damage}"
        );
    }
    assert!(
        raw.messages
            .windows(2)
            .all(|w| w[0].log_time <= w[1].log_time),
        "messages out of log-time order"
    );
    let damage = raw.damage.clone();
    let recorded = Recorded::decode(raw);
    if let Some(damage) = damage {
        assert!(
            recorded.problems.contains(&damage),
            "damage not among the problems"
        );
    }
    let _ = recorded.end();
});
