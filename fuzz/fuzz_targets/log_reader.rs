//! The log reader on damaged logs: every message of every channel is read and
//! decoded, and the last checkpoint looked for. A damaged or cut log must give
//! an error or a truncated end, never a panic or an unbounded allocation.
#![no_main]

use carom_io::{LogCheckpoint, LogReader, ReadOptions};
use libfuzzer_sys::fuzz_target;
use std::io::Cursor;

fuzz_target!(|data: &[u8]| {
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
