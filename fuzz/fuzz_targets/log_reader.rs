//! The log reader on damaged logs: every message of every channel is read and
//! decoded, and the last checkpoint looked for. A damaged or cut log must give
//! an error or a truncated end, never a panic or an unbounded allocation.
#![no_main]

use carom_log::{LogCheckpoint, LogReader, ReadOptions};
use libfuzzer_sys::fuzz_target;
use std::io::Cursor;
use std::sync::Once;

/// The mcap crate (0.26) panics on some damaged lengths (an attachment's data
/// length, a record longer than what is left of its chunk); carom's reader
/// catches those panics and reports the log as malformed (`parse_record` in
/// crates/log/src/read/mod.rs). libFuzzer's hook aborts on every panic, caught
/// or not: this one lets panics raised inside the mcap crate through to carom's
/// catch. A panic anywhere else, or one carom does not catch, still aborts
/// (libfuzzer-sys aborts on a panic that leaves the target).
fn let_caught_mcap_panics_pass() {
    static HOOK: Once = Once::new();
    HOOK.call_once(|| {
        let abort = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            let in_mcap = info
                .location()
                .is_some_and(|l| l.file().contains("/mcap-0."));
            if !in_mcap {
                abort(info);
            }
        }));
    });
}

fuzz_target!(|data: &[u8]| {
    let_caught_mcap_panics_pass();
    let source = Cursor::new(data.to_vec());
    let Ok(mut log) = LogReader::new(source, "fuzz".into(), ReadOptions::default()) else {
        return;
    };
    let _ = log.summary();
    for event in log.events().take(100_000) {
        if event.is_err() {
            break;
        }
    }
    let _ = LogCheckpoint::decode(data);
});
