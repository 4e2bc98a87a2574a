//! Independent reader: the Python `mcap` + `mcap-ros2-support` packages decode carom
//! logs (schemas, CDR messages, JSON thermo, metadata, summary statistics) to the
//! same values the Rust reader gives, for complete files (indexed reading) and for
//! a file cut mid-way (streaming reading).
//!
//! Python is `$CAROM_PYTHON` if set (then the packages must be there), else
//! `python3`; without the packages the test prints that it skipped and passes.

mod mcap_common;

use carom::io::CollisionBatch;
use carom::io::{CollisionDetail, Compression, LogOptions, Stop};
use carom::io::{LogMessage, LogReader};
use carom::run::{run, Control};
use mcap_common::*;
use serde_json::Value;
use std::path::Path;

/// CRC-32 (IEEE, as Python's zlib.crc32), continuing from `crc`.
fn crc32(mut crc: u32, bytes: &[u8]) -> u32 {
    crc = !crc;
    for &b in bytes {
        crc ^= b as u32;
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

fn le<T: Copy, const K: usize>(v: &[T], f: impl Fn(T) -> [u8; K]) -> Vec<u8> {
    v.iter().flat_map(|&x| f(x)).collect()
}

/// What the Rust reader decodes, in the shape the Python script prints.
fn rust_side(path: &Path) -> (Value, u64) {
    let mut r = LogReader::open(path).unwrap();
    let mut crc = std::collections::BTreeMap::<&str, u32>::new();
    let mut batches = Vec::new();
    let mut snaps = Vec::new();
    let mut thermo = Vec::new();
    let mut cps = Vec::new();
    let mut messages = 0u64;
    let add = |crc: &mut std::collections::BTreeMap<&str, u32>, k: &'static str, b: &[u8]| {
        let c = crc.entry(k).or_insert(0);
        *c = crc32(*c, b);
    };
    loop {
        let m = match r.next_message() {
            Ok(Some(m)) => m,
            Ok(None) => break,
            Err(e) => panic!("{e}"),
        };
        messages += 1;
        match m {
            LogMessage::Collisions(b) => {
                let CollisionBatch {
                    first_ordinal,
                    stride,
                    time,
                    kind,
                    i,
                    j,
                    ..
                } = &*b;
                batches.push(serde_json::json!({
                    "first_ordinal": first_ordinal, "stride": stride, "len": time.len(),
                }));
                let f = |v: &[f64]| le(v, f64::to_le_bytes);
                add(&mut crc, "time", &f(time));
                add(&mut crc, "kind", kind);
                add(&mut crc, "i", &le(i, u32::to_le_bytes));
                add(&mut crc, "j", &le(j, u32::to_le_bytes));
                for (k, v) in [
                    ("nx", &b.nx),
                    ("ny", &b.ny),
                    ("vix_before", &b.vix_before),
                    ("viy_before", &b.viy_before),
                    ("vjx_before", &b.vjx_before),
                    ("vjy_before", &b.vjy_before),
                    ("vix_after", &b.vix_after),
                    ("viy_after", &b.viy_after),
                    ("vjx_after", &b.vjx_after),
                    ("vjy_after", &b.vjy_after),
                    ("energy_lost", &b.energy_lost),
                    ("virial", &b.virial),
                ] {
                    add(&mut crc, k, &f(v));
                }
            }
            LogMessage::Snapshot(s) => {
                snaps.push(serde_json::json!({"n": s.len()}));
                add(&mut crc, "s_species", &le(&s.species, u16::to_le_bytes));
                let xs: Vec<f64> = s.positions.iter().map(|p| p.x).collect();
                let ys: Vec<f64> = s.positions.iter().map(|p| p.y).collect();
                let vx: Vec<f64> = s.velocities.iter().map(|p| p.x).collect();
                let vy: Vec<f64> = s.velocities.iter().map(|p| p.y).collect();
                add(&mut crc, "s_x", &le(&xs, f64::to_le_bytes));
                add(&mut crc, "s_y", &le(&ys, f64::to_le_bytes));
                add(&mut crc, "s_vx", &le(&vx, f64::to_le_bytes));
                add(&mut crc, "s_vy", &le(&vy, f64::to_le_bytes));
            }
            LogMessage::Thermo(t) => thermo.push(serde_json::to_value(t).unwrap()),
            LogMessage::Checkpoint(c) => {
                let xs: Vec<f64> = c.engine.positions.iter().map(|p| p.x).collect();
                cps.push(serde_json::json!({
                    "pair_collisions": c.engine.stats.pair_collisions,
                    "wall_collisions": c.engine.stats.wall_collisions,
                    "logged_collisions": c.driver.logged_collisions,
                    "x_crc": crc32(0, &le(&xs, f64::to_le_bytes)),
                    "n": xs.len(),
                }));
            }
        }
    }
    let v = serde_json::json!({
        "crc": crc, "batches": batches, "snapshots": snaps, "thermo": thermo, "checkpoints": cps,
        "run": r.run_map(), "summary": r.summary().unwrap().map(|s| s.to_map()),
    });
    (v, messages)
}

fn compare(py: &Value, rs: &Value) {
    let batches = py["batches"].as_array().unwrap();
    let rb = rs["batches"].as_array().unwrap();
    assert_eq!(batches.len(), rb.len(), "batch count");
    for (p, r) in batches.iter().zip(rb) {
        for k in ["first_ordinal", "stride", "len"] {
            assert_eq!(p[k], r[k], "batch field {k}");
        }
    }
    for (name, _) in [
        ("time", 0),
        ("kind", 0),
        ("i", 0),
        ("j", 0),
        ("nx", 0),
        ("vjy_after", 0),
        ("virial", 0),
        ("energy_lost", 0),
    ] {
        assert_eq!(
            py["batch_crc"][name].as_u64(),
            rs["crc"][name].as_u64().or(Some(0)),
            "CRC of decoded collision field {name}"
        );
    }
    for f in ["species", "x", "y", "vx", "vy"] {
        assert_eq!(
            py["snapshot_crc"][f].as_u64(),
            rs["crc"][format!("s_{f}").as_str()].as_u64().or(Some(0)),
            "CRC of snapshot field {f}"
        );
    }
    assert_eq!(
        py["snapshots"].as_array().unwrap().len(),
        rs["snapshots"].as_array().unwrap().len()
    );
    // Thermo JSON: same numbers (Python parses floats exactly).
    assert_eq!(py["thermo"], rs["thermo"], "thermo records");
    let pc = py["checkpoints"].as_array().unwrap();
    let rc = rs["checkpoints"].as_array().unwrap();
    assert_eq!(pc.len(), rc.len());
    for (p, r) in pc.iter().zip(rc) {
        for k in [
            "pair_collisions",
            "wall_collisions",
            "logged_collisions",
            "x_crc",
            "n",
        ] {
            assert_eq!(p[k], r[k], "checkpoint field {k}");
        }
    }
}

#[test]
fn python_reads_what_rust_reads() {
    let Some(py) = python() else {
        return;
    };
    let system = system(300, 0.45, true, true, 21);
    for (compression, every) in [(Compression::Zstd, 1), (Compression::Lz4, 2)] {
        let out = tmp("python.mcap");
        let log = LogOptions {
            collision_every: every,
            snapshot_interval: Some(1.0),
            thermo_interval: Some(0.25),
            checkpoint_interval: Some(1.5),
            compression,
            // The full record's layout (tests/compact_python.rs replays the compact one).
            collision_detail: CollisionDetail::Full,
            ..LogOptions::default()
        };
        run(
            &spec(system.clone(), Stop::Time(4.0), log),
            &out,
            Control::default(),
        )
        .unwrap();
        let pyv = read_with_python(&py, &out, false);
        assert!(pyv["error"].is_null(), "python: {}", pyv["error"]);
        let (rs, messages) = rust_side(&out);
        compare(&pyv, &rs);
        // Channels, schemas and encodings as documented.
        assert_eq!(
            pyv["channels"]["/collisions"],
            serde_json::json!(["carom_msgs/msg/CollisionBatch", "ros2msg", "cdr"])
        );
        assert_eq!(
            pyv["channels"]["/thermo"],
            serde_json::json!(["carom.Thermo", "jsonschema", "json"])
        );
        assert_eq!(
            pyv["channels"]["/checkpoint"],
            serde_json::json!(["carom_msgs/msg/Checkpoint", "ros2msg", "cdr"])
        );
        // Message counts: Python's iteration, the MCAP statistics record, and Rust agree.
        let counted: u64 = pyv["counts"]
            .as_object()
            .unwrap()
            .values()
            .map(|v| v.as_u64().unwrap())
            .sum();
        assert_eq!(counted, messages);
        assert_eq!(pyv["statistics"], pyv["counts"]);
        assert_eq!(pyv["counts"]["/snapshot"], 5);
        assert_eq!(pyv["counts"]["/thermo"], 17);
        // Metadata records.
        assert_eq!(pyv["metadata"]["carom.run"], rs["run"]);
        assert_eq!(pyv["metadata"]["carom.summary"], rs["summary"]);

        // The same file cut at 60 %: Python's streaming reader and Rust agree on
        // everything before the cut.
        let bytes = std::fs::read(&out).unwrap();
        let cut = tmp("python-cut.mcap");
        std::fs::write(&cut, &bytes[..bytes.len() * 6 / 10]).unwrap();
        let pyv = read_with_python(&py, &cut, true);
        assert!(
            !pyv["error"].is_null(),
            "a cut file ends in an error in Python"
        );
        let (rs, messages) = rust_side(&cut);
        assert!(messages > 10);
        compare(&pyv, &rs);
        let counted: u64 = pyv["counts"]
            .as_object()
            .unwrap()
            .values()
            .map(|v| v.as_u64().unwrap())
            .sum();
        assert_eq!(counted, messages);
        std::fs::remove_file(&out).unwrap();
        std::fs::remove_file(&cut).unwrap();
    }
}
