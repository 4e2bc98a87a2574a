//! Compact collision records (log format 2) read back as the full ones: a compact
//! and a full log of the same run decode to the same collisions — times, discs
//! and every velocity bit for bit, normal, virial and energy lost to rounding —
//! for an elastic periodic fluid, a walled mixture with inelastic walls and
//! normal restitution, and the centre-of-mass rule (whose log stores normals);
//! `carom analyze` gives the same report on both; a compact log resumes; and a
//! run that logs every k-th collision keeps the full record.

use crate::mcap_common::*;
use carom_analysis::{analyze_log, AnalysisOptions, ReadObserver};
use carom_core::{Boundary, Restitution};
use carom_engine::EngineParams;
use carom_log::{
    CollisionDetail, CollisionRecord, LogOptions, LogReader, ReadProgress, Stop,
    COMPACT_COLLISIONS_CHANNEL,
};
use carom_run::{resume, run, Control, ResumeOptions};
use serde_json::Value;
use std::path::Path;

fn log_opts(detail: CollisionDetail) -> LogOptions {
    LogOptions {
        collision_detail: detail,
        snapshot_interval: Some(0.5),
        thermo_interval: Some(0.25),
        checkpoint_interval: Some(1.0),
        ..LogOptions::default()
    }
}

/// The three runs: (name, system, dynamics).
fn cases() -> Vec<(&'static str, carom_engine::SystemSpec, EngineParams)> {
    let mut walled = system(120, 0.35, true, true, 5);
    walled.sim_box.boundary[1] = Boundary::Walls { restitution: 0.9 };
    vec![
        (
            "periodic elastic",
            system(150, 0.4, false, false, 3),
            EngineParams::default(),
        ),
        (
            "walled mixture, normal e = 0.8",
            walled,
            EngineParams {
                restitution: Restitution::Normal(0.8),
                ..EngineParams::default()
            },
        ),
        (
            "centre of mass R = 0.85, t_c = 1e-3",
            system(120, 0.35, false, true, 9),
            EngineParams {
                restitution: Restitution::CentreOfMass(0.85),
                tc: 1e-3,
                ..EngineParams::default()
            },
        ),
    ]
}

fn write(
    name: &str,
    sys: &carom_engine::SystemSpec,
    params: EngineParams,
    log: LogOptions,
) -> std::path::PathBuf {
    let out = tmp(name);
    let mut s = spec(sys.clone(), Stop::Time(3.0), log);
    s.params = params;
    run(&s, &out, Control::default()).unwrap();
    out
}

fn records(path: &Path) -> Vec<CollisionRecord> {
    let mut r = LogReader::open(path).unwrap();
    r.collisions().collect::<Result<_, _>>().unwrap()
}

fn close(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= 1e-12 * scale
}

#[test]
fn compact_and_full_logs_of_one_run_decode_to_the_same_collisions() {
    for (name, sys, params) in cases() {
        let compact = write(
            "compact.mcap",
            &sys,
            params,
            log_opts(CollisionDetail::Compact),
        );
        let full = write("full.mcap", &sys, params, log_opts(CollisionDetail::Full));
        let r = LogReader::open(&compact).unwrap();
        assert_eq!(r.run().log_format, carom_log::LOG_FORMAT_VERSION);
        let mut r = r;
        let _ = r.collisions().next();
        assert!(r.compact_collisions(), "{name}: compact schema expected");
        let (c, f) = (records(&compact), records(&full));
        assert!(c.len() > 300, "{name}: {} collisions", c.len());
        assert_eq!(c.len(), f.len(), "{name}");
        let mut walls = 0;
        for (a, b) in c.iter().zip(&f) {
            let at = format!("{name}: collision {} at t = {}", b.ordinal, b.time);
            assert_eq!(
                (a.ordinal, a.kind, a.i, a.j, a.time.to_bits()),
                (b.ordinal, b.kind, b.i, b.j, b.time.to_bits()),
                "{at}"
            );
            let v = |r: &CollisionRecord| bits(&[r.vi_before, r.vj_before, r.vi_after, r.vj_after]);
            assert_eq!(v(a), v(b), "{at}: velocities");
            assert!(
                (a.normal - b.normal).length() <= 1e-12,
                "{at}: normal {} vs {}",
                a.normal,
                b.normal
            );
            let scale = b.virial.abs().max(1e-300);
            assert!(
                close(a.virial, b.virial, scale),
                "{at}: virial {} vs {}",
                a.virial,
                b.virial
            );
            let k = 0.5 * (a.vi_before.length_squared() + a.vj_before.length_squared()) * 4.0;
            assert!(
                close(a.energy_lost, b.energy_lost, k),
                "{at}: energy lost {} vs {}",
                a.energy_lost,
                b.energy_lost
            );
            walls += a.is_wall() as usize;
        }
        if name.starts_with("walled") {
            assert!(walls > 0, "{name}: no wall collisions");
        }
        // The compact file is much smaller.
        let size = |p: &Path| std::fs::metadata(p).unwrap().len();
        assert!(size(&compact) < size(&full), "{name}");
        for p in [&compact, &full] {
            let _ = std::fs::remove_file(p);
        }
    }
}

struct Quiet;
impl ReadObserver for Quiet {
    fn pass(&mut self, _: &'static str) {}
    fn progress(&mut self, _: ReadProgress) {}
    fn warn(&mut self, _: &str) {}
}

/// Numbers within 1e-9 relative (rounding of virial and energy lost), the rest equal.
fn same_report(a: &Value, b: &Value, path: &str) {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            assert!(
                (x - y).abs() <= 1e-9 * x.abs().max(y.abs()).max(1e-300),
                "{path}: {x} vs {y}"
            );
        }
        (Value::Object(x), Value::Object(y)) => {
            assert_eq!(
                x.keys().collect::<Vec<_>>(),
                y.keys().collect::<Vec<_>>(),
                "{path}"
            );
            for (k, v) in x {
                if k != "file" {
                    same_report(v, &y[k], &format!("{path}.{k}"));
                }
            }
        }
        (Value::Array(x), Value::Array(y)) => {
            assert_eq!(x.len(), y.len(), "{path}");
            for (k, (u, v)) in x.iter().zip(y).enumerate() {
                same_report(u, v, &format!("{path}[{k}]"));
            }
        }
        _ => assert_eq!(a, b, "{path}"),
    }
}

#[test]
fn analyze_gives_the_same_report_on_compact_and_full_logs() {
    for (name, sys, params) in cases().into_iter().take(2) {
        let compact = write(
            "a-compact.mcap",
            &sys,
            params,
            log_opts(CollisionDetail::Compact),
        );
        let full = write("a-full.mcap", &sys, params, log_opts(CollisionDetail::Full));
        let report = |p: &Path| {
            let (r, complete) = analyze_log(p, AnalysisOptions::default(), &mut Quiet).unwrap();
            assert!(complete, "{name}");
            serde_json::to_value(r).unwrap()
        };
        let (a, b) = (report(&compact), report(&full));
        assert!(
            a.get("pressure").is_some_and(|p| !p.is_null()),
            "{name}: {a}"
        );
        same_report(&a, &b, name);
        for p in [&compact, &full] {
            let _ = std::fs::remove_file(p);
        }
    }
}

/// A compact log cut and resumed continues with compact records that still replay
/// bit for bit (against an uninterrupted run's full log).
#[test]
fn a_resumed_compact_log_replays() {
    let (_, sys, params) = cases().swap_remove(1);
    let full = write("r-full.mcap", &sys, params, log_opts(CollisionDetail::Full));
    let mut s = spec(
        sys.clone(),
        Stop::Time(1.6),
        log_opts(CollisionDetail::Compact),
    );
    s.params = params;
    let first = tmp("r-first.mcap");
    run(&s, &first, Control::default()).unwrap();
    let resumed = tmp("r-resumed.mcap");
    let opts = ResumeOptions {
        stop: Some(Stop::Time(3.0)),
    };
    resume(&first, &resumed, &opts, Control::default()).unwrap();
    let (c, f) = (records(&resumed), records(&full));
    assert_eq!(c.len(), f.len());
    for (a, b) in c.iter().zip(&f) {
        assert_eq!(
            (a.ordinal, a.i, a.j, a.time.to_bits()),
            (b.ordinal, b.i, b.j, b.time.to_bits())
        );
        assert_eq!(
            bits(&[a.vi_after, a.vj_after]),
            bits(&[b.vi_after, b.vj_after])
        );
    }
    for p in [&full, &first, &resumed] {
        let _ = std::fs::remove_file(p);
    }
}

/// With collision_every > 1 the log keeps the full record (compact records need
/// every collision to replay velocities).
#[test]
fn a_strided_log_keeps_the_full_record() {
    let sys = system(100, 0.3, false, false, 4);
    let log = LogOptions {
        collision_every: 3,
        ..log_opts(CollisionDetail::Compact)
    };
    let out = write("strided.mcap", &sys, EngineParams::default(), log);
    let mut r = LogReader::open(&out).unwrap();
    assert_eq!(r.run().log.collision_detail, CollisionDetail::Full);
    let recs: Vec<_> = r.collisions().collect::<Result<_, _>>().unwrap();
    assert!(!r.compact_collisions());
    assert!(recs.len() > 10 && recs.iter().all(|c| c.ordinal % 3 == 0));
    assert_ne!(
        COMPACT_COLLISIONS_CHANNEL.schema_name,
        carom_log::CHANNELS[0].schema_name
    );
    let _ = std::fs::remove_file(&out);
}

/// A log of format 1.2 (full records, no `collision_detail` in its options):
/// made here by copying a full log's messages under 1.2 metadata, as `carom
/// repair` copies. It reads (info, analyze) and resumes, continuing with full
/// records and its own format version.
#[test]
fn a_format_1_log_reads_and_resumes() {
    use carom_log::{scan, LogWriter, WriterOptions, WriterPosition};
    let (_, sys, params) = cases().swap_remove(1);
    let mut s = spec(
        sys.clone(),
        Stop::Time(1.5),
        log_opts(CollisionDetail::Full),
    );
    s.params = params;
    let new = tmp("v2-full.mcap");
    run(&s, &new, Control::default()).unwrap();
    let old = tmp("v1.mcap");
    {
        let mut reader = LogReader::open(&new).unwrap();
        let mut map = reader.run_map().clone();
        map.insert("log_format".into(), "1.2".into());
        let mut log: Value = serde_json::from_str(&map["log_options"]).unwrap();
        log.as_object_mut().unwrap().remove("collision_detail");
        map.insert("log_options".into(), log.to_string());
        let mut w = LogWriter::create(
            &old,
            WriterOptions::from_log_options(&reader.run().log),
            &map,
            WriterPosition::default(),
        )
        .unwrap();
        while let Some(m) = reader.next_raw().unwrap() {
            w.copy_message(m.channel, m.sequence, m.log_time, m.publish_time, m.data)
                .unwrap();
        }
        let summary = reader.summary().unwrap().unwrap();
        w.finish(&summary.to_map()).unwrap();
    }
    let info = scan(&old).unwrap();
    assert_eq!(info.run.log_format, "1.2");
    assert_eq!(info.run.log.collision_detail, CollisionDetail::Full);
    assert_eq!(records(&old), records(&new));
    analyze_log(&old, AnalysisOptions::default(), &mut Quiet).unwrap();
    let resumed = tmp("v1-resumed.mcap");
    let opts = ResumeOptions {
        stop: Some(Stop::Time(3.0)),
    };
    resume(&old, &resumed, &opts, Control::default()).unwrap();
    let mut r = LogReader::open(&resumed).unwrap();
    assert_eq!(r.run().log_format, "1.2");
    let got: Vec<_> = r.collisions().collect::<Result<_, _>>().unwrap();
    assert!(!r.compact_collisions());
    let full = write(
        "v1-reference.mcap",
        &sys,
        params,
        log_opts(CollisionDetail::Full),
    );
    assert_eq!(got, records(&full));
    for p in [&new, &old, &resumed, &full] {
        let _ = std::fs::remove_file(p);
    }
}
