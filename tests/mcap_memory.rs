//! Reading streams: the peak memory of this process stays far below the size of
//! the log it writes, then reads in full and copies whole (`repair`) (Linux only: it reads VmHWM from
//! /proc/self/status). Alone in its test binary so nothing else inflates the peak
//! (the other integration tests share one binary, tests/integration).

#[path = "integration/mcap_common.rs"]
mod mcap_common;
#[path = "integration/readers_common.rs"]
mod readers_common;

use carom_log::{CollisionDetail, Compression, LogOptions, Stop};
use carom_log::{LogEnd, LogReader};
use carom_run::{run, Control};
use mcap_common::*;

/// Peak resident set size of this process (bytes), if the OS tells.
fn peak_rss() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

#[test]
fn reading_a_large_log_takes_bounded_memory() {
    if peak_rss().is_none() {
        eprintln!("SKIPPED: no /proc/self/status on this system");
        return;
    }
    let out = tmp("large.mcap");
    let log = LogOptions {
        snapshot_interval: None,
        thermo_interval: None,
        checkpoint_interval: None,
        compression: Compression::None,
        // The full record: the test needs a log of more than 150 MB.
        collision_detail: CollisionDetail::Full,
        ..LogOptions::default()
    };
    let n = 1_500_000;
    let s = run(
        &spec(system(2000, 0.5, false, false, 6), Stop::Collisions(n), log),
        &out,
        Control::default(),
    )
    .unwrap();
    assert!(s.file_bytes > 150_000_000, "{} bytes", s.file_bytes);
    let mut r = LogReader::open(&out).unwrap();
    let mut count = 0u64;
    let mut t_prev = f64::NEG_INFINITY;
    for c in r.collisions() {
        let c = c.unwrap();
        assert!(c.time >= t_prev);
        t_prev = c.time;
        count += 1;
    }
    assert_eq!(count, n);
    assert_eq!(*r.end(), LogEnd::Complete);
    drop(r);
    // Copying the whole log (what `repair` does, and `resume` with the prefix up
    // to its checkpoint) takes bounded memory too: the message buffers the
    // writer thread hands back are reused, not queued.
    let copy = tmp("large-copy.mcap");
    let repaired = carom_run::repair(&out, &copy).unwrap();
    assert!(repaired.bytes >= s.file_bytes / 10 * 9, "{repaired:?}");
    std::fs::remove_file(&copy).unwrap();
    let peak = peak_rss().unwrap();
    eprintln!("peak RSS {peak} bytes, log {} bytes", s.file_bytes);
    std::fs::remove_file(&out).unwrap();
    assert!(
        peak < s.file_bytes / 3 && peak < 100_000_000,
        "peak RSS {peak} bytes for a {} byte log",
        s.file_bytes
    );
}
