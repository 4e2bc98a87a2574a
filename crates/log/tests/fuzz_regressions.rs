//! Inputs that `cargo fuzz` (fuzz/) found to break the log reader, kept as
//! regression tests: every file in `tests/fuzz_regressions/` is read as a log
//! to its end, with every message decoded. Reading must end in a value or an
//! error, never a panic (these tests build with overflow checks on, as the
//! fuzzer does).

use carom_log::{LogCheckpoint, LogReader, ReadOptions};
use std::io::Cursor;

#[test]
fn inputs_the_fuzzer_found_read_without_panicking() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fuzz_regressions");
    let mut files = 0;
    for entry in std::fs::read_dir(dir).expect("the regression inputs") {
        let path = entry.unwrap().path();
        let data = std::fs::read(&path).unwrap();
        files += 1;
        let source = Cursor::new(data.clone());
        if let Ok(mut log) =
            LogReader::new(source, path.display().to_string(), ReadOptions::default())
        {
            let _ = log.summary();
            let mut read = 0;
            for event in log.events() {
                read += 1;
                if event.is_err() || read > 100_000 {
                    break;
                }
            }
        }
        let _ = LogCheckpoint::decode(&data);
    }
    assert!(files >= 2, "{files} regression inputs in {dir}");
}
