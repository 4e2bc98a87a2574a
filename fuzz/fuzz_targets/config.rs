//! The configuration front end on arbitrary input: the first line-separated block
//! is the JSON text, every later line a `--set key=value`. Whatever the input,
//! reading, overriding, checking and resolving it returns a value or an error,
//! never a panic.
#![no_main]

use carom_config::Config;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let (json, sets) = text.split_once("\n\n").unwrap_or((text, ""));
    let sets: Vec<String> = sets.lines().take(8).map(str::to_owned).collect();
    if let Ok(config) = Config::from_json_with_sets(json, "fuzz", &sets) {
        let _ = config.to_run_spec();
        let _ = config.canonical_json();
    }
});
