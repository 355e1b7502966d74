//! Fuzzes the serial link's reply parser: the input is one raw line from the firmware
//! (any bytes, line end or not). Any input must give a reply or `None`, never a crash.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = navdeck::link::serial::protocol::parse_reply(data);
});
