//! Independent reader, field by field: the Python `mcap` + `mcap-ros2-support`
//! packages (`tests/python/read_carom_log.py --fields`) decode EVERY field of
//! EVERY message of carom logs — full and compact collision records (with and
//! without normals), snapshots, thermo, checkpoints, `/scene` frames — and the
//! metadata records, and each must equal the Rust reader's view of it
//! (`tests/log_view_common`) exactly: floats bit for bit, the same set of keys at
//! every level (so a field one side has and the other lacks fails), the same
//! envelope (sequence, log and publish time), channels and schema texts. This is
//! what catches a field swapped consistently in a writer and its reader: the file
//! would no longer match its published schema. Complete files are read with the
//! indexed reader, a cut one with the streaming reader.
//!
//! Python is `$CAROM_PYTHON` if set (then the packages must be there), else
//! `python3`; without the packages the test skips, loudly, or fails when `CI` is
//! set (tests/readers_common).

use crate::log_view_common as view;
use crate::mcap_common::*;
use carom_core::Restitution;
use carom_engine::EngineParams;
use carom_log::{CollisionDetail, Compression, LogOptions, Stop};
use carom_log::{CHANNELS, CH_COLLISIONS, COMPACT_COLLISIONS_CHANNEL, TOPICS};
use carom_run::{run, Control};
use serde_json::{json, Value};
use std::path::Path;

/// Every field of every message of `path` as the Python readers decode it.
fn read_every_field(py: &str, path: &Path, streaming: bool) -> Value {
    let flags: &[&str] = if streaming {
        &["--fields", "--streaming"]
    } else {
        &["--fields"]
    };
    python_reader(py, path, flags)
}

/// Where `py` and `rs` first differ, below `at`: a key only one side has, an
/// array length, or a leaf value (floats are hex bit patterns on both sides).
fn first_difference(py: &Value, rs: &Value, at: &str) -> Option<String> {
    match (py, rs) {
        (Value::Object(p), Value::Object(r)) => {
            let keys = |m: &serde_json::Map<String, Value>| m.keys().cloned().collect::<Vec<_>>();
            if keys(p) != keys(r) {
                return Some(format!(
                    "{at}: python has the fields {:?}, rust {:?}",
                    keys(p),
                    keys(r)
                ));
            }
            p.iter()
                .find_map(|(k, v)| first_difference(v, &r[k], &format!("{at}.{k}")))
        }
        (Value::Array(p), Value::Array(r)) if p.len() != r.len() => Some(format!(
            "{at}: python has {} entries, rust {}",
            p.len(),
            r.len()
        )),
        (Value::Array(p), Value::Array(r)) => p
            .iter()
            .zip(r)
            .enumerate()
            .find_map(|(k, (a, b))| first_difference(a, b, &format!("{at}[{k}]"))),
        _ if py == rs => None,
        _ => Some(format!("{at}: python {py}, rust {rs}")),
    }
}

fn assert_same(py: &Value, rs: &Value, what: &str) {
    if let Some(d) = first_difference(py, rs, what) {
        panic!("the Python and Rust readers disagree: {d}");
    }
}

/// Python's messages of `path` against Rust's, field by field; `complete` = the
/// file as written (its snapshots give the `/scene` frames' expected content).
fn compare_messages(pyv: &Value, path: &Path, complete: &Path) -> usize {
    let rs = view::messages(path, complete);
    let py = pyv["messages"].as_array().unwrap();
    assert_eq!(py.len(), rs.len(), "messages in {}", path.display());
    for (k, (p, r)) in py.iter().zip(&rs).enumerate() {
        let what = format!("message {k} ({} #{})", r["topic"], r["sequence"]);
        assert_same(p, r, &what);
    }
    // What each topic's messages were decoded with: the published schema.
    for m in &rs {
        let topic = m["topic"].as_str().unwrap();
        let k = TOPICS.iter().position(|t| *t == topic).unwrap();
        let ch = match k {
            CH_COLLISIONS if m["fields"].get("dpx").is_some() => COMPACT_COLLISIONS_CHANNEL,
            _ => CHANNELS[k],
        };
        let want = json!([ch.schema_name, ch.schema_encoding, ch.message_encoding]);
        assert_eq!(pyv["channels"][topic], want, "{topic}");
        assert_eq!(pyv["schemas"][topic], ch.schema_text, "{topic}");
    }
    rs.len()
}

/// A case: its name, engine parameters, log options and whether the box has walls.
fn cases() -> Vec<(&'static str, EngineParams, LogOptions, bool)> {
    let observed = LogOptions {
        snapshot_interval: Some(1.0),
        thermo_interval: Some(0.25),
        checkpoint_interval: Some(1.5),
        ..LogOptions::default()
    };
    let inelastic = |rule| EngineParams {
        restitution: rule,
        tc: 1e-4,
        ..EngineParams::default()
    };
    vec![
        (
            "full records, inelastic (e = 0.9), walls, zstd, scene frames",
            inelastic(Restitution::Normal(0.9)),
            LogOptions {
                collision_detail: CollisionDetail::Full,
                scene_interval: Some(1.0),
                ..observed
            },
            true,
        ),
        (
            "full records of every 2nd collision, periodic, lz4",
            EngineParams::default(),
            LogOptions {
                collision_every: 2,
                compression: Compression::Lz4,
                ..observed
            },
            false,
        ),
        (
            "compact records, elastic, walls, zstd",
            EngineParams::default(),
            observed.clone(),
            true,
        ),
        (
            "compact records with normals (centre-of-mass R = 0.9), periodic, uncompressed",
            inelastic(Restitution::CentreOfMass(0.9)),
            LogOptions {
                compression: Compression::None,
                ..observed
            },
            false,
        ),
    ]
}

#[test]
fn python_reads_every_field_that_rust_reads() {
    let Some(py) = python() else {
        return;
    };
    for (k, (name, params, log, walls)) in cases().into_iter().enumerate() {
        let out = tmp("python.mcap");
        let mut s = spec(
            system(200, 0.45, walls, true, 21 + k as u64),
            Stop::Time(3.0),
            log.clone(),
        );
        s.params = params;
        // A metadata key that only some runs have.
        s.max_time_without_collision = Some(100.0);
        run(&s, &out, Control::default()).unwrap();
        let pyv = read_every_field(&py, &out, false);
        assert!(pyv["error"].is_null(), "{name}: python: {}", pyv["error"]);
        let messages = compare_messages(&pyv, &out, &out);
        // Every metadata record, every key, and no other record.
        assert_same(&pyv["metadata"], &view::metadata(&out), "metadata");
        // Message counts: Python's iteration, the MCAP statistics and Rust agree.
        let counted: u64 = pyv["counts"]
            .as_object()
            .unwrap()
            .values()
            .map(|v| v.as_u64().unwrap())
            .sum();
        assert_eq!(counted, messages as u64, "{name}");
        assert_eq!(pyv["statistics"], pyv["counts"], "{name}");
        assert_eq!(pyv["counts"]["/snapshot"], 4, "{name}");
        assert_eq!(pyv["counts"]["/thermo"], 13, "{name}");
        assert!(pyv["collisions"].as_u64().unwrap() > 500, "{name}");
        if log.scene_interval.is_some() {
            assert_eq!(pyv["counts"]["/scene"], 4, "{name}");
        }

        // The file cut at 60 %: Python's streaming reader and Rust agree on every
        // message before the cut.
        if k == 0 {
            let bytes = std::fs::read(&out).unwrap();
            let cut = tmp("python-cut.mcap");
            std::fs::write(&cut, &bytes[..bytes.len() * 6 / 10]).unwrap();
            let pyv = read_every_field(&py, &cut, true);
            assert!(!pyv["error"].is_null(), "a cut file ends in an error");
            let messages = compare_messages(&pyv, &cut, &out);
            assert!(messages > 10, "{messages} messages before the cut");
            std::fs::remove_file(&cut).unwrap();
        }
        std::fs::remove_file(&out).unwrap();
    }
}

/// The Python block of docs/log-format.md, "Reading logs from Python", run as it
/// stands: it decodes every message of every channel (the `/thermo` JSON too, where
/// a ros2 decoder alone stops with `DecoderNotFoundError`), and its counts per
/// topic are the log's.
#[test]
fn the_documented_python_loop_decodes_every_channel() {
    let Some(py) = python() else {
        return;
    };
    let doc =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/log-format.md"))
            .unwrap();
    let section = &doc[doc
        .find("## Reading logs from Python")
        .expect("the section")..];
    let start = section.find("```python\n").expect("a python block") + "```python\n".len();
    let code = &section[start..start + section[start..].find("```").unwrap()];
    let script = tmp("documented_loop.py");
    std::fs::write(&script, code).unwrap();
    let out = tmp("documented_loop.mcap");
    let mut s = spec(
        system(200, 0.45, true, true, 5),
        Stop::Time(3.0),
        LogOptions {
            snapshot_interval: Some(1.0),
            thermo_interval: Some(0.25),
            checkpoint_interval: Some(1.5),
            scene_interval: Some(1.0),
            ..LogOptions::default()
        },
    );
    s.params = EngineParams::default();
    run(&s, &out, Control::default()).unwrap();
    let ran = std::process::Command::new(&py)
        .arg(&script)
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        ran.status.success(),
        "the documented loop fails:\n{}",
        String::from_utf8_lossy(&ran.stderr)
    );
    let counts: Value = serde_json::from_slice(&ran.stdout).unwrap();
    let info = carom_log::scan(&out).unwrap();
    for (k, topic) in TOPICS.iter().enumerate() {
        let want = info.messages[k];
        let got = counts[*topic].as_u64().unwrap_or(0);
        assert_eq!(
            got, want,
            "{topic}: the loop decoded {got}, the log has {want}"
        );
    }
    assert!(counts["/thermo"].as_u64().unwrap() >= 12, "{counts}");
    std::fs::remove_file(&out).unwrap();
}
