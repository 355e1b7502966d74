//! Measurements of the serial link on the emulated firmware, which takes the wire time of
//! every byte at its baud rate. Not a pass/fail test: run it by hand and read the figures.
//!
//! cargo test --test suite serial_measure:: -- --ignored --nocapture

use crate::serial_emulator;

use navdeck::config::Config;
use navdeck::link::serial::SerialLink;
use navdeck::link::serial::protocol::Request;
use navdeck::link::serial::transport::{Counters, Transport};
use serial_emulator::Emulator;
use std::time::{Duration, Instant};

fn percentile(sorted: &[f64], p: f64) -> f64 {
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

#[test]
#[ignore = "a measurement, not a test: run with --ignored --nocapture"]
fn round_trip_and_encoder_poll_rate_at_57600_baud() {
    let emu = Emulator::start();
    // Counts of a robot that has driven a while: a reply of 18 bytes with its CR LF.
    emu.set_counts(1_234_567.0, -1_234_567.0);
    let port = serialport::new(emu.path(), 57600)
        .timeout(Duration::from_secs(1))
        .open()
        .unwrap();
    let mut transport = Transport::new(port);
    let counters = Counters::default();
    let timeout = Duration::from_millis(250);
    for (request, n) in [(Request::Encoders, 2000), (Request::Motors(0, 0), 1000)] {
        let mut times = Vec::with_capacity(n);
        for _ in 0..n {
            // From the request written to its reply parsed.
            let start = Instant::now();
            transport.transact(request, timeout, 0, &counters).unwrap();
            times.push(start.elapsed().as_secs_f64() * 1e3);
        }
        times.sort_by(f64::total_cmp);
        println!(
            "round trip `{request}` x{n}: median {:.2} ms, p99 {:.2} ms, max {:.2} ms",
            percentile(&times, 0.5),
            percentile(&times, 0.99),
            times[n - 1]
        );
    }
    let s = counters.snapshot();
    assert_eq!(s.timeouts + s.garbage, 0, "{s:?}");
    drop(transport);

    // The link's own worker asked for more encoder readings than the wire can carry.
    let mut config = Config::default();
    config.serial.poll_hz = 10_000.0;
    let link = SerialLink::open(&emu.path(), &config.serial, &config.robot).unwrap();
    let (n0, t0) = (link.stats().readings, Instant::now());
    emu.wait_frames(90);
    let (n1, t1) = (link.stats().readings, Instant::now());
    let rate = (n1 - n0) as f64 / (t1 - t0).as_secs_f64();
    println!(
        "encoder polls achieved at 57600 baud: {rate:.0} per second over {:.1} s ({} readings); stats {:?}",
        (t1 - t0).as_secs_f64(),
        n1 - n0,
        link.stats()
    );
}
