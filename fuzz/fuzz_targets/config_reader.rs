//! Fuzzes the config reader: the input, as lossy UTF-8, is a config file's TOML. Any input
//! must give a config or an error, never a crash; a config it accepts must pass
//! `validate` and must survive a round trip through `toml::to_string` and the reader again.
#![no_main]

use libfuzzer_sys::fuzz_target;
use navdeck::config::Config;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let path = Path::new("fuzz.toml");
    let Ok(config) = Config::parse(&text, path) else {
        return;
    };
    if let Err(e) = config.validate(path) {
        panic!("an accepted config fails validate: {e}");
    }
    let again = toml::to_string(&config).expect("an accepted config serialises to TOML");
    if let Err(e) = Config::parse(&again, path) {
        panic!("a re-serialised config is refused: {e}\n--- re-serialised:\n{again}");
    }
});
