//! A run's MCAP log holds exactly what the engine did: every collision (bit for
//! bit, pair and wall), snapshots at the requested exact times, thermo records,
//! checkpoints, and the metadata records; the same under every compression, with
//! every k-th collision, with a collision budget, and when stopped by the flag.

use crate::mcap_common::*;
use carom_engine::{Engine, EngineParams, Event, SystemSpec};
use carom_log::StopReason;
use carom_log::{
    scan, scan_indexed, scan_observed, LogEnd, LogEvent, LogMessage, LogReader, ReadProgress,
};
use carom_log::{CollisionRecord, KIND_WALL};
use carom_log::{Compression, LogOptions, Stop};
use carom_run::{run, Control, Progress};
use std::sync::atomic::{AtomicBool, Ordering};

fn log_opts(compression: Compression) -> LogOptions {
    LogOptions {
        collisions: true,
        collision_every: 1,
        collision_detail: Default::default(),
        snapshot_interval: Some(1.0),
        snapshot_schedule: None,
        thermo_interval: Some(0.5),
        checkpoint_interval: Some(2.0),
        scene_interval: None,
        compression,
        flush_seconds: 1.0,
    }
}

fn read_collisions(path: &std::path::Path) -> Vec<CollisionRecord> {
    let mut r = LogReader::open(path).unwrap();
    let v: Vec<_> = r.collisions().collect::<Result<_, _>>().unwrap();
    assert_eq!(*r.end(), LogEnd::Complete);
    v
}

fn matches_event(rec: &CollisionRecord, ev: &Event) -> bool {
    same_as_engine(rec, ev)
}

#[test]
fn log_holds_exactly_what_the_engine_did() {
    let system = system(300, 0.45, true, true, 11);
    let t_end = 5.0;
    let out = tmp("roundtrip.mcap");
    let summary = run(
        &spec(
            system.clone(),
            Stop::Time(t_end),
            log_opts(Compression::Zstd),
        ),
        &out,
        Control::default(),
    )
    .unwrap();
    assert_eq!(summary.stop_reason, StopReason::Time);
    assert_eq!(summary.sim_time, t_end);

    // Collisions: identical to a bare engine's, in order, pair and wall.
    let (events, mut bare) = reference_collisions(&system, EngineParams::default(), t_end);
    let logged = read_collisions(&out);
    assert!(events.len() > 2_000, "only {} collisions", events.len());
    assert_eq!(logged.len(), events.len());
    let walls = logged.iter().filter(|c| c.kind == KIND_WALL).count();
    assert!(walls > 50, "only {walls} wall collisions");
    for (k, (rec, ev)) in logged.iter().zip(&events).enumerate() {
        assert_eq!(rec.ordinal, k as u64);
        assert!(matches_event(rec, ev), "collision {k}: {rec:?} vs {ev:?}");
    }
    assert_eq!(
        summary.pair_collisions + summary.wall_collisions,
        events.len() as u64
    );
    assert_eq!(summary.logged_collisions, events.len() as u64);

    // Snapshots at exactly t = 0, 1, …, 5, equal to the bare engine's states.
    let mut r = LogReader::open(&out).unwrap();
    assert_eq!(r.run().seed, 11);
    assert_eq!(r.run().n_discs, 300);
    assert_eq!(r.run().stop, Stop::Time(t_end));
    assert!(r.run().config.contains("\"test\": true"));
    let snaps: Vec<_> = r
        .snapshots()
        .map(|m| match m.unwrap() {
            LogMessage::Snapshot(s) => s,
            other => panic!("{other:?}"),
        })
        .collect();
    assert_eq!(
        snaps.iter().map(|s| s.time).collect::<Vec<_>>(),
        [0.0, 1.0, 2.0, 3.0, 4.0, 5.0]
    );
    let mut replay = Engine::new(system.build().unwrap(), EngineParams::default()).unwrap();
    for s in &snaps {
        replay.run_until(s.time).unwrap();
        let st = replay.state();
        assert_eq!(bits(&s.positions), bits(&st.positions), "t = {}", s.time);
        assert_eq!(bits(&s.velocities), bits(&st.velocities));
        assert_eq!(s.species, st.species_of);
        assert_eq!(s.species_mass, [1.0, 3.0]);
        assert_eq!(s.boundary, [0, 1]);
    }
    let summary_rec = r.summary().unwrap().expect("summary record");
    assert_eq!(summary_rec.stop_reason, StopReason::Time);
    assert_eq!(summary_rec.sim_time, t_end);

    // Thermo every 0.5 and checkpoints at 0, 2, 4 and the end.
    let mut r = LogReader::open(&out).unwrap();
    let thermo: Vec<_> = r
        .thermo()
        .map(|m| match m.unwrap() {
            LogMessage::Thermo(t) => t,
            other => panic!("{other:?}"),
        })
        .collect();
    assert_eq!(thermo.len(), 11);
    for (k, t) in thermo.iter().enumerate() {
        assert_eq!(t.time, 0.5 * k as f64);
        // Observations come before any collision at the same instant.
        let done = events.iter().filter(|e| e.time() < t.time).count() as u64;
        assert_eq!(t.collisions, done, "thermo at {}", t.time);
        assert!((t.temperature - 1.0).abs() < 1e-9, "elastic: kT stays 1");
    }
    assert!(thermo[0].z.is_none() && thermo[0].pressure.is_none());
    let z = thermo.last().unwrap().z.unwrap();
    assert!(z > 1.5 && z < 6.0, "walls: Z = {z}");
    let mut r = LogReader::open(&out).unwrap();
    let cps: Vec<_> = r
        .checkpoints()
        .map(|m| match m.unwrap() {
            LogMessage::Checkpoint(c) => c,
            other => panic!("{other:?}"),
        })
        .collect();
    assert_eq!(
        cps.iter().map(|c| c.engine.now).collect::<Vec<_>>(),
        [0.0, 2.0, 4.0, 5.0]
    );
    bare.run_until(t_end).unwrap();
    let last = Engine::from_checkpoint(cps[3].engine.clone()).unwrap();
    assert_eq!(bits(&last.state().positions), bits(&bare.state().positions));
    assert_eq!(
        bits(&last.state().velocities),
        bits(&bare.state().velocities)
    );

    // events(): everything interleaved in time order.
    let mut r = LogReader::open(&out).unwrap();
    let mut t_prev = f64::NEG_INFINITY;
    let (mut nc, mut ns) = (0, 0);
    for e in r.events() {
        let e = e.unwrap();
        assert!(e.time() >= t_prev, "{} after {t_prev}", e.time());
        t_prev = e.time();
        match e {
            LogEvent::Collision(_) => nc += 1,
            LogEvent::Snapshot(_) => ns += 1,
            _ => {}
        }
    }
    assert_eq!((nc, ns), (events.len(), 6));

    // scan(): counts and span without decoding.
    let info = scan(&out).unwrap();
    assert_eq!(info.end, LogEnd::Complete);
    assert_eq!(info.messages[1..], [6, 11, 4, 0]);
    assert_eq!(info.logged_collisions, events.len() as u64);
    assert_eq!(info.last_checkpoint_time, Some(5.0));
    assert_eq!(info.channels, [true, true, true, true, false], "no /scene");
    assert!(info.summary.is_some());

    // The index of a finished log gives the same, reading only a few chunks.
    assert_eq!(scan_indexed(&out).unwrap(), Some(info.clone()));

    // The scan reports how far through the file it is: rising, ending at the
    // file's length, and otherwise the same scan.
    let mut seen: Vec<ReadProgress> = Vec::new();
    let observed = scan_observed(&out, &mut |p| seen.push(p)).unwrap();
    assert_eq!(observed, info);
    let bytes = std::fs::metadata(&out).unwrap().len();
    assert!(seen.len() >= 2, "{seen:?}");
    assert!(seen.iter().all(|p| p.file_bytes == bytes));
    assert!(seen.windows(2).all(|w| w[0].bytes_read <= w[1].bytes_read));
    assert!(seen[0].bytes_read < bytes);
    assert_eq!(seen.last().unwrap().bytes_read, bytes);
    assert_eq!(seen.last().unwrap().fraction(), 1.0);
    // So does a reader, message by message.
    let mut r = LogReader::open(&out).unwrap();
    let mut last = r.progress();
    assert!(last.bytes_read > 0 && last.bytes_read <= bytes);
    while r.next_raw().unwrap().is_some() {
        let now = r.progress();
        assert!(now.bytes_read >= last.bytes_read);
        last = now;
    }
    assert!(
        last.bytes_read < bytes,
        "the index records at the end are still unread"
    );
    assert_eq!(r.progress().bytes_read, bytes, "reading has ended");
    std::fs::remove_file(&out).unwrap();
}

#[test]
fn compressions_and_every_kth_collision() {
    let system = system(200, 0.5, false, false, 5);
    let (events, _) = reference_collisions(&system, EngineParams::default(), 3.0);
    let mut first: Option<Vec<CollisionRecord>> = None;
    for c in [Compression::Zstd, Compression::Lz4, Compression::None] {
        let out = tmp("compression.mcap");
        run(
            &spec(system.clone(), Stop::Time(3.0), log_opts(c)),
            &out,
            Control::default(),
        )
        .unwrap();
        let recs = read_collisions(&out);
        assert_eq!(recs.len(), events.len());
        assert_eq!(
            scan_indexed(&out).unwrap(),
            Some(scan(&out).unwrap()),
            "{c:?}"
        );
        match &first {
            None => first = Some(recs),
            Some(f) => assert_eq!(f, &recs, "{c:?}"),
        }
        std::fs::remove_file(&out).unwrap();
    }
    let out = tmp("every3.mcap");
    let opts = LogOptions {
        collision_every: 3,
        ..log_opts(Compression::Zstd)
    };
    run(
        &spec(system.clone(), Stop::Time(3.0), opts),
        &out,
        Control::default(),
    )
    .unwrap();
    let recs = read_collisions(&out);
    assert_eq!(recs.len(), events.len().div_ceil(3));
    assert_eq!(scan_indexed(&out).unwrap(), Some(scan(&out).unwrap()));
    for r in &recs {
        assert_eq!(r.ordinal % 3, 0);
        assert!(matches_event(r, &events[r.ordinal as usize]));
    }
    // Collisions off: the channel exists but is empty.
    let opts = LogOptions {
        collisions: false,
        ..log_opts(Compression::Zstd)
    };
    run(
        &spec(system.clone(), Stop::Time(3.0), opts),
        &out,
        Control::default(),
    )
    .unwrap();
    assert!(read_collisions(&out).is_empty());
    let indexed = scan_indexed(&out).unwrap().expect("a finished log");
    assert_eq!(indexed.time_span[0], None);
    assert_eq!(indexed, scan(&out).unwrap());
    std::fs::remove_file(&out).unwrap();
}

#[test]
fn collision_budget_and_stop_flag() {
    let system = system(200, 0.5, false, false, 9);
    let out = tmp("budget.mcap");
    let s = run(
        &spec(
            system.clone(),
            Stop::Collisions(12_345),
            log_opts(Compression::Zstd),
        ),
        &out,
        Control::default(),
    )
    .unwrap();
    assert_eq!(s.stop_reason, StopReason::Collisions);
    assert_eq!(s.pair_collisions + s.wall_collisions, 12_345);
    assert_eq!(read_collisions(&out).len(), 12_345);

    // The stop flag, raised from the progress callback, ends the run cleanly.
    let stop = AtomicBool::new(false);
    let mut calls = 0;
    let mut cb = |p: &Progress| {
        calls += 1;
        if p.collisions > 50_000 {
            stop.store(true, Ordering::Relaxed);
        }
    };
    let control = Control {
        stop: Some(&stop),
        progress: Some(&mut cb),
        progress_interval: std::time::Duration::ZERO,
        ..Control::default()
    };
    let s = run(
        &spec(system, Stop::Time(1e8), log_opts(Compression::Zstd)),
        &out,
        control,
    )
    .unwrap();
    assert!(calls > 0);
    assert_eq!(s.stop_reason, StopReason::Interrupted);
    let mut r = LogReader::open(&out).unwrap();
    let n = r.collisions().count() as u64;
    assert_eq!(n, s.pair_collisions + s.wall_collisions);
    assert_eq!(*r.end(), LogEnd::Complete);
    let sm = r.summary().unwrap().unwrap();
    assert_eq!(sm.stop_reason, StopReason::Interrupted);
    std::fs::remove_file(&out).unwrap();
}

#[test]
fn bad_options_name_the_field() {
    let system = system(50, 0.3, false, false, 1);
    let out = tmp("bad.mcap");
    let opts = LogOptions {
        snapshot_interval: Some(0.0),
        ..LogOptions::default()
    };
    let e = run(
        &spec(system, Stop::Time(1.0), opts),
        &out,
        Control::default(),
    )
    .unwrap_err();
    assert!(e.to_string().contains("log.snapshot_interval"), "{e}");
}

#[test]
fn docs_show_every_schema_verbatim() {
    use carom_log::CHECKPOINT_MSG;
    use carom_log::{
        COLLISION_BATCH_MSG, COMPACT_COLLISION_BATCH_MSG, SNAPSHOT_MSG, THERMO_JSON_SCHEMA,
    };
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/log-format.md"))
        .unwrap();
    for (name, text) in [
        ("CollisionBatch", COLLISION_BATCH_MSG),
        ("CompactCollisionBatch", COMPACT_COLLISION_BATCH_MSG),
        ("Snapshot", SNAPSHOT_MSG),
        ("Checkpoint", CHECKPOINT_MSG),
        ("Thermo", THERMO_JSON_SCHEMA),
    ] {
        assert!(
            doc.contains(text),
            "docs/log-format.md does not show the current {name} schema"
        );
    }
}

#[test]
fn relaxed_placement_reports_progress_and_the_stop_flag_ends_it_before_the_log() {
    use carom_engine::{Placement, PlacementProgress};
    use carom_run::RunError;
    let system = SystemSpec {
        placement: Placement::Relaxed,
        ..system(400, 0.82, false, false, 2)
    };
    // To the end: a report at every step (interval 0), the last one with nothing
    // left too close, then the run.
    let out = tmp("placed.mcap");
    let place_and_run = |stop: f64, control: Control| {
        run(
            &spec(
                system.clone(),
                Stop::Time(stop),
                log_opts(Compression::None),
            ),
            &out,
            control,
        )
    };
    let mut seen: Vec<PlacementProgress> = Vec::new();
    let mut show = |p: &PlacementProgress| seen.push(*p);
    let control = Control {
        placing: Some(&mut show),
        progress_interval: std::time::Duration::ZERO,
        ..Control::default()
    };
    let s = place_and_run(0.1, control).unwrap();
    assert_eq!(s.stop_reason, StopReason::Time);
    let (last, before) = seen.split_last().unwrap();
    assert!(before.len() > 10, "{} reports", before.len());
    assert!(before
        .iter()
        .enumerate()
        .all(|(k, p)| p.steps == k && p.close > 0));
    assert_eq!((last.steps, last.close), (before.len(), 0));
    std::fs::remove_file(&out).unwrap();
    // The stop flag raised at step 3: placement ends there and no log is created.
    let stop = AtomicBool::new(false);
    let mut show = |p: &PlacementProgress| {
        if p.steps == 3 {
            stop.store(true, Ordering::Relaxed);
        }
    };
    let control = Control {
        stop: Some(&stop),
        placing: Some(&mut show),
        progress_interval: std::time::Duration::ZERO,
        ..Control::default()
    };
    let e = place_and_run(0.1, control).unwrap_err();
    assert!(
        matches!(e, RunError::InterruptedPlacing { steps: 3 }),
        "{e}"
    );
    assert!(!out.exists());
    // Options are checked before placement, not a minute later.
    let mut show = |p: &PlacementProgress| panic!("placement started: {p:?}");
    let control = Control {
        placing: Some(&mut show),
        ..Control::default()
    };
    let e = place_and_run(1e12, control).unwrap_err();
    assert!(e.to_string().contains("stop.time"), "{e}");
}

#[test]
fn snapshots_and_checkpoints_reuse_their_buffers_without_mixing_them_up() {
    // Snapshots and checkpoints are encoded into buffers handed back by the
    // writer once written: on the writer thread and inline alike, every message
    // must hold its own state, also when a checkpoint (larger) and snapshots of
    // another engine (another N) alternate.
    use carom_log::{LogWriter, WriterOptions, WriterPosition};
    use std::collections::BTreeMap;
    for background in [true, false] {
        let out = tmp("reuse.mcap");
        let opts = WriterOptions {
            background,
            ..WriterOptions::default()
        };
        let meta = test_run_metadata(500);
        let mut w =
            LogWriter::create(&out, opts, &meta.to_map(), WriterPosition::default()).unwrap();
        let mut a = Engine::new(
            system(500, 0.4, false, false, 1).build().unwrap(),
            EngineParams::default(),
        )
        .unwrap();
        let mut b = Engine::new(
            system(90, 0.3, true, true, 2).build().unwrap(),
            EngineParams::default(),
        )
        .unwrap();
        let mut states = Vec::new();
        let mut checkpoints = Vec::new();
        for k in 0..6 {
            a.run_collisions(2000).unwrap();
            b.run_collisions(300).unwrap();
            let s = if k % 2 == 0 { a.state() } else { b.state() };
            w.write_snapshot(&s).unwrap();
            states.push(s);
            if k % 3 == 1 {
                let c = a.checkpoint();
                w.write_checkpoint(c.clone(), 0.0).unwrap();
                checkpoints.push(c);
            }
        }
        w.finish(&BTreeMap::new()).unwrap();
        let mut r = LogReader::open(&out).unwrap();
        let snaps: Vec<_> = r
            .snapshots()
            .map(|m| match m.unwrap() {
                LogMessage::Snapshot(s) => s,
                other => panic!("{other:?}"),
            })
            .collect();
        assert_eq!(snaps.len(), states.len(), "background {background}");
        for (s, st) in snaps.iter().zip(&states) {
            assert_eq!(s.time, st.time);
            assert_eq!(
                bits(&s.positions),
                bits(&st.positions),
                "background {background}"
            );
            assert_eq!(bits(&s.velocities), bits(&st.velocities));
            assert_eq!(s.species, st.species_of);
        }
        let mut r = LogReader::open(&out).unwrap();
        let cps: Vec<_> = r
            .checkpoints()
            .map(|m| match m.unwrap() {
                LogMessage::Checkpoint(c) => c.engine,
                other => panic!("{other:?}"),
            })
            .collect();
        assert_eq!(cps.len(), checkpoints.len(), "background {background}");
        assert!(
            cps == checkpoints,
            "background {background}: checkpoints differ"
        );
        std::fs::remove_file(&out).unwrap();
    }
}

#[test]
fn the_log_describes_its_run() {
    // A walled mixture with inelastic collisions, every 3rd collision logged.
    let system = system(200, 0.35, true, true, 5);
    let params = EngineParams {
        restitution: carom_core::Restitution::Normal(0.9),
        tc: 1e-3,
        ..EngineParams::default()
    };
    let log = LogOptions {
        collision_every: 3,
        ..log_opts(Compression::Zstd)
    };
    let out = tmp("facts.mcap");
    let run_spec = carom_log::RunSpec {
        params,
        ..spec(system.clone(), Stop::Time(0.5), log.clone())
    };
    run(&run_spec, &out, Control::default()).unwrap();
    let r = LogReader::open(&out).unwrap();
    assert_eq!(r.run().log_format, carom_log::LOG_FORMAT_VERSION);
    let facts = r
        .run()
        .run_facts
        .clone()
        .expect("a 1.2 log stores its facts");
    assert_eq!(
        facts,
        carom_log::RunFacts::new(&system.species, &system.sim_box, &params, &log)
    );
    assert_eq!(facts.species, system.species);
    assert_eq!(facts.sim_box, system.sim_box);
    assert_eq!(facts.restitution, carom_core::Restitution::Normal(0.9));
    assert_eq!(facts.tc, 1e-3);
    assert_eq!(facts.n_discs, 200);
    assert_eq!(facts.collision_every, Some(3));
    assert_eq!(
        facts.accessible_area,
        carom_core::observables::accessible_area(&system.species, &system.sim_box)
    );
}

#[test]
fn a_log_of_format_1_1_reads_without_facts() {
    use carom_log::{LogWriter, WriterOptions, WriterPosition};
    // The `carom.run` record of a 1.1 log: every key but `run_facts`.
    let mut meta = test_run_metadata(4);
    meta.log_format = "1.1".into();
    let map = meta.to_map();
    assert!(!map.contains_key("run_facts"));
    let out = tmp("old.mcap");
    let mut w = LogWriter::create(
        &out,
        WriterOptions::default(),
        &map,
        WriterPosition::default(),
    )
    .unwrap();
    w.finish(&std::collections::BTreeMap::new()).unwrap();
    let r = LogReader::open(&out).unwrap();
    assert_eq!(r.run().log_format, "1.1");
    assert_eq!(r.run().run_facts, None);
    assert_eq!(*r.run(), meta);
}
