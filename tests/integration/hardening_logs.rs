//! Issue 51, faults 8 and 9: every log carom writes reads back, and one flipped
//! bit loses at most the chunk it hits.
//!
//! Fault 8 builds its logs through the writer API (a real run's log copied with
//! non-finite `/thermo` values and a NaN kinetic energy in `carom.summary`, as
//! a runaway error or `thermostat.kT=1e308` leaves them), since no short
//! configuration reliably produces them. Fault 9 flips single bits in a small
//! run's log, in each kind of region, and runs the readers on it.

use std::path::Path;

use crate::cli_common::{carom, json_of, ok, scratch};
use carom_log::{
    LogEnd, LogReader, LogWriter, SummaryMetadata, Thermo, WriterOptions, WriterPosition, CH_THERMO,
};

/// A small run's log, closing a chunk at every checkpoint (every 2 time units).
fn small_log(dir: &Path, name: &str) {
    ok(&carom(
        dir,
        &[
            "run",
            "--force",
            "-q",
            "--out",
            name,
            "--set",
            "species.0.count=200",
            "--set",
            "stop.duration=10",
            "--set",
            "log.snapshot_interval=2",
            "--set",
            "log.checkpoint_interval=2",
        ],
    ));
}

/// Copy `input` to `out` through the writer, with every `/thermo` record given
/// K = +∞, kT = +∞, Z = NaN and the summary's K = NaN.
fn with_non_finite_values(input: &Path, out: &Path) {
    let mut r = LogReader::open(input).unwrap();
    let mut w = LogWriter::create(
        out,
        WriterOptions::from_log_options(&r.run().log),
        &r.run_map().clone(),
        WriterPosition::default(),
    )
    .unwrap();
    while let Some(m) = r.next_raw().unwrap() {
        if m.channel == CH_THERMO {
            let mut t = Thermo::decode(m.data).unwrap();
            t.kinetic_energy = f64::INFINITY;
            t.temperature = f64::INFINITY;
            t.z = Some(f64::NAN);
            w.write_thermo(&t).unwrap();
        } else {
            w.copy_message(m.channel, m.sequence, m.log_time, m.publish_time, m.data)
                .unwrap();
        }
    }
    let mut s: SummaryMetadata = r.summary().unwrap().unwrap();
    s.kinetic_energy = f64::NAN;
    s.energy_lost = f64::NEG_INFINITY;
    w.finish(&s.to_map()).unwrap();
}

#[test]
fn non_finite_values_in_thermo_and_summary_read_back_everywhere() {
    let dir = scratch("non-finite");
    small_log(&dir, "s.mcap");
    with_non_finite_values(&dir.join("s.mcap"), &dir.join("nan.mcap"));
    // The library reads back exactly what was written.
    let mut r = LogReader::open(&dir.join("nan.mcap")).unwrap();
    let mut thermo = 0;
    for t in r.thermo() {
        let carom_log::LogMessage::Thermo(t) = t.unwrap() else {
            panic!("not a thermo record")
        };
        assert!(
            t.temperature == f64::INFINITY && t.z.unwrap().is_nan(),
            "{t:?}"
        );
        thermo += 1;
    }
    assert!(thermo > 2);
    let s = r.summary().unwrap().unwrap();
    assert!(s.kinetic_energy.is_nan() && s.energy_lost == f64::NEG_INFINITY);
    // Every command reads it.
    let info = json_of(&carom(&dir, &["info", "nan.mcap", "--json", "--verify"]));
    assert_eq!(info["complete"], true, "{info}");
    assert_eq!(info["summary"]["stop_reason"], "time", "{info}");
    ok(&carom(&dir, &["info", "nan.mcap"]));
    ok(&carom(&dir, &["analyze", "nan.mcap", "--json"]));
    let out = ok(&carom(&dir, &["repair", "nan.mcap", "--out", "r.mcap"]));
    assert!(out.contains("already complete"), "{out}");
    // The repaired log keeps the summary: it does not claim the run can go on.
    let info = ok(&carom(&dir, &["info", "r.mcap", "--verify"]));
    assert!(info.contains("summary: stopped (time)"), "{info}");
    assert!(!info.contains("carom resume"), "{info}");
}

/// The top-level MCAP records of `b`: (offset, opcode, end).
fn records(b: &[u8]) -> Vec<(usize, u8, usize)> {
    let mut pos = 8;
    let mut out = Vec::new();
    while pos + 9 <= b.len() - 8 {
        let len = u64::from_le_bytes(b[pos + 1..pos + 9].try_into().unwrap()) as usize;
        out.push((pos, b[pos], pos + 9 + len));
        pos += 9 + len;
    }
    out
}

#[test]
fn a_flipped_bit_loses_at_most_its_chunk_and_verify_names_it() {
    let dir = scratch("flips");
    small_log(&dir, "s.mcap");
    let src = std::fs::read(dir.join("s.mcap")).unwrap();
    let recs = records(&src);
    let chunks: Vec<_> = recs.iter().filter(|r| r.1 == 0x06).collect();
    assert!(
        chunks.len() >= 4,
        "a log of several chunks: {}",
        chunks.len()
    );
    let data_end = recs.iter().find(|r| r.1 == 0x0F).unwrap().0;
    let summary = recs.iter().rfind(|r| r.1 == 0x0C).unwrap();
    // The reference: what every message of the intact log is.
    let all = |path: &Path| {
        let mut r = LogReader::open(path).unwrap();
        let mut v = Vec::new();
        while let Some(m) = r.next_raw().unwrap() {
            v.push((m.channel, m.sequence, m.data.to_vec()));
        }
        (v, r.end().clone())
    };
    let (reference, end) = all(&dir.join("s.mcap"));
    assert_eq!(end, LogEnd::Complete);
    let flip = |at: usize, bit: u8| {
        let mut b = src.clone();
        b[at] ^= 1 << bit;
        std::fs::write(dir.join("f.mcap"), &b).unwrap();
    };
    let mut cases = 0;
    // In the data section after the last chunk (the summary record's values, the
    // data-end record's CRC): the data section's CRC fails; in a log whose
    // metadata carry checksums (format 2.3) that held for `carom.run`, every
    // message has been read: the end is damaged (a summary whose checksum fails
    // is named and left out), and `repair` copies every chunk.
    for at in [summary.2 - 3, data_end + 10] {
        flip(at, 2);
        let (read, end) = all(&dir.join("f.mcap"));
        assert_eq!(read, reference, "flip at {at}: every message, unchanged");
        let LogEnd::Damaged { detail } = end else {
            panic!("flip at {at}: {end:?}")
        };
        assert!(
            detail.contains("Data section CRC failed"),
            "flip at {at}: {detail}"
        );
        if at < data_end {
            assert!(detail.contains("carom.summary: checksum fails"), "{detail}");
        }
        let out = carom(&dir, &["info", "--verify", "f.mcap"]);
        assert!(!out.status.success(), "flip at {at}: --verify passed");
        ok(&carom(
            &dir,
            &["repair", "f.mcap", "--out", "r.mcap", "--force"],
        ));
        let (repaired, end) = all(&dir.join("r.mcap"));
        assert_eq!(
            (repaired == reference, end),
            (true, LogEnd::Complete),
            "flip at {at}"
        );
        cases += 1;
    }
    // After the data section: the index, the footer, the end magic. Every reader
    // reads everything, and says the end is damaged.
    let after = data_end + 13;
    let tail: Vec<usize> = (after..src.len())
        .step_by((src.len() - after) / 12 + 1)
        .chain([src.len() - 30, src.len() - 12, src.len() - 3])
        .collect();
    for (k, &at) in tail.iter().enumerate() {
        flip(at, (k % 8) as u8);
        let (read, end) = all(&dir.join("f.mcap"));
        assert_eq!(read, reference, "flip at {at}: every message, unchanged");
        assert!(
            matches!(end, LogEnd::Damaged { .. }),
            "flip at {at}: {end:?}"
        );
        let out = carom(&dir, &["info", "--verify", "f.mcap"]);
        assert!(!out.status.success(), "flip at {at}: --verify passed");
        assert!(String::from_utf8_lossy(&out.stderr).contains("damaged"));
        let out = carom(&dir, &["analyze", "f.mcap", "--json"]);
        assert!(out.status.success(), "flip at {at}: analyze refused");
        assert!(String::from_utf8_lossy(&out.stderr).contains("damaged"));
        ok(&carom(
            &dir,
            &[
                "export", "f.mcap", "--format", "xyz", "--out", "f.xyz", "--force",
            ],
        ));
        ok(&carom(
            &dir,
            &["repair", "f.mcap", "--out", "r.mcap", "--force"],
        ));
        let (repaired, end) = all(&dir.join("r.mcap"));
        assert_eq!(
            (repaired == reference, end),
            (true, LogEnd::Complete),
            "flip at {at}"
        );
        cases += 1;
    }
    // Inside a chunk (past its header, in the compressed records): repair keeps
    // every other chunk and names the lost one; --verify fails.
    for (k, c) in chunks.iter().enumerate().filter(|(_, c)| c.2 - c.0 > 200) {
        for at in [c.0 + 100, (c.0 + c.2) / 2, c.2 - 20] {
            flip(at, (at % 8) as u8);
            let out = carom(&dir, &["info", "--verify", "f.mcap"]);
            assert!(
                !out.status.success(),
                "chunk {k}, flip at {at}: --verify passed"
            );
            let err = String::from_utf8_lossy(&out.stderr);
            assert!(err.contains("corrupted") && err.contains("f.mcap"), "{err}");
            let out = carom(&dir, &["repair", "f.mcap", "--out", "r.mcap", "--force"]);
            let err = String::from_utf8_lossy(&out.stderr).into_owned();
            ok(&out);
            assert!(
                // (with the message indexes after it, up to the next chunk)
                err.contains(&format!("lost: bytes {}..", c.0)),
                "chunk {k} at {}..{}, flip at {at}: {err}",
                c.0,
                c.2
            );
            // Every message of the other chunks is there, in order; the lost
            // chunk's are not.
            let (repaired, _) = all(&dir.join("r.mcap"));
            let mut i = 0;
            for m in &repaired {
                while i < reference.len() && reference[i] != *m {
                    i += 1;
                }
                assert!(i < reference.len(), "a message the log never held");
            }
            assert!(repaired.len() < reference.len());
            let lost_ok = reference.len() - repaired.len();
            assert!(lost_ok > 0);
            cases += 1;
        }
    }
    assert!(cases >= 24, "{cases} flips");
}
