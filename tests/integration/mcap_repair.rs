//! A log cut between flushes (as by SIGKILL) holds only complete records, so
//! strict readers open it: carom's reader, the Python `mcap` readers and
//! `@mcap/core`'s stream reader (what Foxglove uses; `tests/node/read.mjs`, run
//! when node and `npm install --prefix tests/node` are there, skipped with a
//! message otherwise). `carom repair` turns it into a complete, indexed log with
//! the same messages.
//!
//! The cut is taken deterministically: an inline writer (no thread) with a large
//! chunk and no timed flush is fed more than the file buffer holds after its last
//! flush, and the file is copied while the chunk is still open.

use crate::mcap_common::*;
use carom_engine::{Engine, EngineParams};
use carom_log::{Compression, LogEnd, LogReader, LogWriter, WriterOptions, WriterPosition};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

type Raw = (usize, u32, u64, u64, Vec<u8>);

fn raw_messages(path: &Path) -> (Vec<Raw>, LogEnd) {
    let mut r = LogReader::open(path).unwrap();
    let mut v = Vec::new();
    while let Some(m) = r.next_raw().unwrap() {
        v.push((
            m.channel,
            m.sequence,
            m.log_time,
            m.publish_time,
            m.data.to_vec(),
        ));
    }
    (v, r.end().clone())
}

/// Snapshots flushed before the cut.
const FLUSHED: usize = 3;

/// A log cut while a chunk of over 1 MiB (more than the writer's file buffer) is
/// open after [`FLUSHED`] flushed snapshots.
fn cut_log(name: &str) -> PathBuf {
    let live = tmp(&format!("{name}-live.mcap"));
    let cut = tmp(&format!("{name}.mcap"));
    let opts = WriterOptions {
        background: false,
        compression: Compression::None,
        chunk_size: 64 << 20,
        flush_every: Duration::from_secs(1 << 20),
        ..WriterOptions::default()
    };
    let meta = test_run_metadata(2000);
    let mut w = LogWriter::create(&live, opts, &meta.to_map(), WriterPosition::default()).unwrap();
    let mut e = Engine::new(
        system(2000, 0.4, false, false, 5).build().unwrap(),
        EngineParams::default(),
    )
    .unwrap();
    for _ in 0..FLUSHED {
        e.run_collisions(200).unwrap();
        w.write_snapshot(&e.state()).unwrap();
    }
    w.flush().unwrap();
    for _ in 0..40 {
        e.run_collisions(50).unwrap();
        w.write_snapshot(&e.state()).unwrap();
    }
    std::fs::copy(&live, &cut).unwrap();
    drop(w);
    cut
}

/// Every record of `path` after the magic is whole: its length fits in the file.
fn assert_whole_records(path: &Path) {
    let bytes = std::fs::read(path).unwrap();
    let mut pos = 8usize;
    while pos + 9 <= bytes.len() {
        let op = bytes[pos];
        let len = u64::from_le_bytes(bytes[pos + 1..pos + 9].try_into().unwrap());
        let left = (bytes.len() - pos - 9) as u64;
        assert!(
            len <= left,
            "record at byte {pos} (opcode {op:#04x}) claims {len} bytes; {left} are left"
        );
        pos += 9 + len as usize;
    }
    assert_eq!(pos, bytes.len(), "the file ends inside a record header");
}

fn carom(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_carom"))
        .args(args)
        .output()
        .expect("carom runs")
}

#[test]
fn a_log_cut_between_flushes_holds_only_whole_records_that_every_reader_opens() {
    let cut = cut_log("repair-cut");
    assert_whole_records(&cut);
    let (msgs, end) = raw_messages(&cut);
    assert!(matches!(end, LogEnd::Truncated { .. }), "{end:?}");
    assert_eq!(msgs.len(), FLUSHED);
    if let Some(py) = python() {
        let v = read_with_python(&py, &cut, true);
        assert_eq!(
            v["counts"]["/snapshot"].as_u64(),
            Some(FLUSHED as u64),
            "{v}"
        );
    }
    if let Some(v) = node_read(&cut) {
        assert_eq!(
            v["messages"]["/snapshot"].as_u64(),
            Some(FLUSHED as u64),
            "{v}"
        );
        assert_eq!(v["complete"], Value::Bool(false), "{v}");
    }
}

#[test]
fn repair_writes_a_complete_indexed_log_with_the_cut_logs_messages() {
    let cut = cut_log("repair-in");
    let (msgs, _) = raw_messages(&cut);
    let out = tmp("repair-out.mcap");
    let _ = std::fs::remove_file(&out);
    let o = carom(&[
        "repair",
        cut.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        stdout.contains("wrote") && stdout.contains("3 messages"),
        "{stdout}"
    );
    let (repaired, end) = raw_messages(&out);
    assert_eq!(end, LogEnd::Complete);
    assert_eq!(repaired, msgs);
    let info = carom(&["info", "--json", out.to_str().unwrap()]);
    assert!(info.status.success());
    let v: Value = serde_json::from_slice(&info.stdout).unwrap();
    assert_eq!(v["complete"], Value::Bool(true), "{v}");
    if let Some(py) = python() {
        // The non-streaming reader needs the summary section and its indexes.
        let v = read_with_python(&py, &out, false);
        assert!(v["error"].is_null(), "{v}");
        assert_eq!(
            v["counts"]["/snapshot"].as_u64(),
            Some(FLUSHED as u64),
            "{v}"
        );
    }
    if let Some(v) = node_read(&out) {
        assert_eq!(v["complete"], Value::Bool(true), "{v}");
        assert_eq!(
            v["messages"]["/snapshot"].as_u64(),
            Some(FLUSHED as u64),
            "{v}"
        );
    }

    // Without --out: beside the input, never over it; an existing output needs
    // --force; the input as --out is refused.
    let default = cut.with_extension("repaired.mcap");
    let _ = std::fs::remove_file(&default);
    let before = std::fs::read(&cut).unwrap();
    let o = carom(&["repair", cut.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stdout).contains(default.to_str().unwrap()));
    assert_eq!(raw_messages(&default).0, msgs);
    assert_eq!(
        std::fs::read(&cut).unwrap(),
        before,
        "the input is untouched"
    );
    let o = carom(&["repair", cut.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--force"));
    assert!(carom(&["repair", cut.to_str().unwrap(), "--force"])
        .status
        .success());
    let o = carom(&["repair", cut.to_str().unwrap(), "-o", cut.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("that is the input"));
    let missing = tmp("repair-missing.mcap");
    let o = carom(&[
        "repair",
        missing.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "-f",
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(carom(&["repair"]).status.code(), Some(2));
}
