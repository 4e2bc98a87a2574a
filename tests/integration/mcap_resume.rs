//! Resume: a log cut anywhere (a crash) and resumed from its last checkpoint holds
//! exactly the messages of the uninterrupted run, byte for byte; a finished run
//! resumed with a later stop equals a run made that long from the start; resuming
//! in place replaces the file only when done; a file without a checkpoint or a stop
//! before the checkpoint is a clear error.

use crate::mcap_common::*;
use carom_log::StopReason;
use carom_log::{scan, scan_indexed, LogEnd, LogEvent, LogReader, ReadError, ReadProgress};
use carom_log::{CollisionDetail, Compression, LogOptions, Stop};
use carom_log::{LogWriter, WriterOptions, WriterPosition};
use carom_run::{resume, run, Control, ResumeOptions, ResumePass, RunError};
use std::collections::BTreeMap;
use std::path::Path;

type Raw = (usize, u32, u64, u64, Vec<u8>);

fn raw_messages(path: &Path) -> Vec<Raw> {
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
    assert_eq!(*r.end(), LogEnd::Complete);
    v
}

fn log_opts() -> LogOptions {
    LogOptions {
        collisions: true,
        collision_every: 1,
        collision_detail: Default::default(),
        snapshot_interval: Some(1.0),
        snapshot_schedule: None,
        thermo_interval: Some(0.5),
        checkpoint_interval: Some(2.0),
        scene_interval: None,
        compression: Compression::Zstd,
        flush_seconds: 1.0,
    }
}

#[test]
fn a_cut_log_resumes_to_the_same_bytes() {
    let system = system(300, 0.45, true, true, 3);
    let full = tmp("full.mcap");
    let s_full = run(
        &spec(system, Stop::Time(8.0), log_opts()),
        &full,
        Control::default(),
    )
    .unwrap();
    let expected = raw_messages(&full);
    let bytes = std::fs::read(&full).unwrap();
    for frac in [0.3, 0.55, 0.9] {
        let cut = tmp("cut.mcap");
        std::fs::write(&cut, &bytes[..(bytes.len() as f64 * frac) as usize]).unwrap();
        let out = tmp("resumed.mcap");
        // The reading of the input is reported: the search for the checkpoint
        // through the whole file, then the copy up to it.
        let mut reads: Vec<(ResumePass, ReadProgress)> = Vec::new();
        let mut reading = |pass, p| reads.push((pass, p));
        let control = Control {
            reading: Some(&mut reading),
            ..Control::default()
        };
        let s = resume(&cut, &out, &ResumeOptions::default(), control).unwrap();
        let cut_bytes = std::fs::metadata(&cut).unwrap().len();
        let copying = reads
            .iter()
            .position(|r| r.0 == ResumePass::Copying)
            .expect("the copy is reported");
        let (search, copy) = reads.split_at(copying);
        assert!(!search.is_empty(), "cut at {frac}: the search is reported");
        assert!(search.iter().all(|r| r.0 == ResumePass::FindingCheckpoint));
        assert!(copy.iter().all(|r| r.0 == ResumePass::Copying));
        for pass in [search, copy] {
            assert!(pass
                .windows(2)
                .all(|w| w[0].1.bytes_read <= w[1].1.bytes_read));
            assert!(pass.iter().all(|r| r.1.file_bytes == cut_bytes));
        }
        assert_eq!(search.last().unwrap().1.bytes_read, cut_bytes);
        let copied = copy.last().unwrap().1.bytes_read;
        assert!(copied > 0 && copied <= cut_bytes, "{copied} of {cut_bytes}");
        assert!(s.collisions_this_process > 0);
        assert_eq!(
            (s.pair_collisions, s.wall_collisions, s.sim_time),
            (s_full.pair_collisions, s_full.wall_collisions, 8.0)
        );
        let got = raw_messages(&out);
        assert_eq!(got.len(), expected.len(), "cut at {frac}");
        for (k, (a, b)) in got.iter().zip(&expected).enumerate() {
            assert!(a == b, "message {k} differs after resuming a cut at {frac}");
        }
        let r = LogReader::open(&out).unwrap();
        assert_eq!(
            r.run().resumed_from.as_deref(),
            Some(cut.display().to_string().as_str())
        );
        let mut meta = r.run_map().clone();
        meta.remove("resumed_from");
        meta.remove("resumed_at");
        // (Each record's checksum covers its own keys: compared without it.)
        meta.remove("crc32");
        let full_reader = LogReader::open(&full).unwrap();
        let mut full_meta = full_reader.run_map().clone();
        full_meta.remove("crc32");
        assert_eq!(meta, full_meta);
        for p in [&cut, &out] {
            std::fs::remove_file(p).unwrap();
        }
    }

    // In place: the cut file is replaced by the complete log, nothing else is left.
    let cut = tmp("inplace.mcap");
    std::fs::write(&cut, &bytes[..bytes.len() / 2]).unwrap();
    let s = resume(&cut, &cut, &ResumeOptions::default(), Control::default()).unwrap();
    assert_eq!(s.log, cut);
    assert_eq!(raw_messages(&cut), expected);
    let mut tmpname = cut.file_name().unwrap().to_os_string();
    tmpname.push(".resume-tmp");
    assert!(!cut.with_file_name(tmpname).exists());
    std::fs::remove_file(&cut).unwrap();
    std::fs::remove_file(&full).unwrap();
}

/// A dense run on neighbour lists (η = 0.72, a channel, so with walls and
/// periodic images) cut in the middle resumes on lists from its last
/// checkpoint to the same bytes as the uninterrupted run.
#[test]
fn a_cut_log_on_lists_resumes_to_the_same_bytes() {
    let system = system(400, 0.72, true, false, 5);
    let on = carom_engine::Engine::new(system.build().unwrap(), Default::default());
    assert!(
        on.unwrap().neighbour_lists(),
        "auto chooses lists at η = 0.72"
    );
    let full = tmp("lists-full.mcap");
    run(
        &spec(system, Stop::Time(6.0), log_opts()),
        &full,
        Control::default(),
    )
    .unwrap();
    let expected = raw_messages(&full);
    let bytes = std::fs::read(&full).unwrap();
    let cut = tmp("lists-cut.mcap");
    std::fs::write(&cut, &bytes[..bytes.len() * 3 / 5]).unwrap();
    let out = tmp("lists-resumed.mcap");
    let s = resume(&cut, &out, &ResumeOptions::default(), Control::default()).unwrap();
    assert!(s.collisions_this_process > 0);
    let got = raw_messages(&out);
    let differ: Vec<(usize, usize)> = got
        .iter()
        .zip(&expected)
        .enumerate()
        .filter(|(_, (a, b))| a != b)
        .map(|(k, (a, _))| (k, a.0))
        .collect();
    assert!(
        got.len() == expected.len() && differ.is_empty(),
        "the resumed log differs: {} and {} messages, differing (index, channel): {:?}",
        got.len(),
        expected.len(),
        &differ[..differ.len().min(12)]
    );
    for p in [&cut, &out, &full] {
        std::fs::remove_file(p).unwrap();
    }
}

fn events(path: &Path) -> Vec<LogEvent> {
    let mut r = LogReader::open(path).unwrap();
    r.events().collect::<Result<_, _>>().unwrap()
}

#[test]
fn a_finished_run_extends_like_a_longer_run() {
    let system = system(250, 0.5, false, false, 8);
    let short = tmp("short.mcap");
    run(
        &spec(system.clone(), Stop::Time(6.0), log_opts()),
        &short,
        Control::default(),
    )
    .unwrap();
    let extended = tmp("extended.mcap");
    let s = resume(
        &short,
        &extended,
        &ResumeOptions {
            stop: Some(Stop::Time(10.0)),
        },
        Control::default(),
    )
    .unwrap();
    assert_eq!(s.sim_time, 10.0);
    let long = tmp("long.mcap");
    run(
        &spec(system, Stop::Time(10.0), log_opts()),
        &long,
        Control::default(),
    )
    .unwrap();
    let (a, b) = (events(&extended), events(&long));
    // Same collisions, snapshots and thermo records, in the same order; the
    // checkpoints hold the same engine states (their lists of pending stop events
    // differ: the extended run still carries the old stop).
    assert_eq!(a.len(), b.len());
    for (k, (x, y)) in a.iter().zip(&b).enumerate() {
        match (x, y) {
            (LogEvent::Checkpoint(p), LogEvent::Checkpoint(q)) => {
                assert_eq!(p.engine.now, q.engine.now);
                assert_eq!(bits(&p.engine.positions), bits(&q.engine.positions));
                assert_eq!(bits(&p.engine.velocities), bits(&q.engine.velocities));
                assert_eq!(p.engine.stats, q.engine.stats);
            }
            _ => assert!(x == y, "event {k}: {x:?} vs {y:?}"),
        }
    }
    // The extended run's summary covers the whole run.
    let mut r = LogReader::open(&extended).unwrap();
    let n = r.collisions().count() as u64;
    let sm = r.summary().unwrap().unwrap();
    assert_eq!(sm.pair_collisions + sm.wall_collisions, n);
    // Its index tells what a scan of the whole file does.
    for p in [&short, &extended] {
        assert_eq!(scan_indexed(p).unwrap(), Some(scan(p).unwrap()));
    }
    for p in [&short, &extended, &long] {
        std::fs::remove_file(p).unwrap();
    }
}

/// The events of a log other than checkpoints and thermo records (a run stopped
/// early writes one of each more, at its stop).
fn observations(path: &Path) -> Vec<LogEvent> {
    events(path)
        .into_iter()
        .filter(|e| matches!(e, LogEvent::Collision(_) | LogEvent::Snapshot(_)))
        .collect()
}

#[test]
fn a_run_stops_with_a_finished_log_before_its_disk_fills() {
    let system = system(1000, 0.45, false, true, 5);
    let stop = Stop::Time(80.0);
    let full = tmp("roomy.mcap");
    // Full records: the test needs a log of more than 18 MB.
    let log = LogOptions {
        collision_detail: CollisionDetail::Full,
        ..log_opts()
    };
    run(
        &spec(system.clone(), stop, log.clone()),
        &full,
        Control::default(),
    )
    .unwrap();
    let full_bytes = std::fs::metadata(&full).unwrap().len();
    // A disk with room for 12 MB of log (less than the whole run's log: the run must
    // stop), told through the caller's free-space answer.
    const ROOM: u64 = 12_000_000;
    assert!(
        full_bytes > ROOM + ROOM / 2,
        "the test needs a bigger log: {full_bytes}"
    );
    let cut = tmp("tight.mcap");
    let mut looks = 0;
    let mut free = |p: &Path| -> std::io::Result<u64> {
        looks += 1;
        Ok(ROOM.saturating_sub(std::fs::metadata(p)?.len()))
    };
    let s = run(
        &spec(system, stop, log),
        &cut,
        Control {
            free_space: Some(&mut free),
            progress_interval: std::time::Duration::ZERO,
            ..Control::default()
        },
    )
    .unwrap();
    assert!(looks > 10, "the disk was looked at {looks} times");
    assert_eq!(s.stop_reason, StopReason::DiskFull);
    assert!(s.sim_time > 0.0 && s.sim_time < 80.0, "{}", s.sim_time);
    // What the run kept in hand was enough to finish the log: it fits the room,
    // and it is complete, with its summary.
    let cut_bytes = std::fs::metadata(&cut).unwrap().len();
    assert!(cut_bytes <= ROOM, "the finished log took {cut_bytes} bytes");
    assert!(
        cut_bytes > ROOM / 3,
        "stopped far too early: {cut_bytes} bytes"
    );
    let mut r = LogReader::open(&cut).unwrap();
    let logged = r.collisions().count() as u64;
    assert_eq!(*r.end(), LogEnd::Complete);
    let sm = r
        .summary()
        .unwrap()
        .expect("a finished log has its summary");
    assert_eq!(sm.stop_reason, StopReason::DiskFull);
    assert_eq!(sm.logged_collisions, logged);
    assert_eq!(sm.sim_time, s.sim_time);
    // Resumed in place on a disk with less room than the log takes, it is refused
    // at once: the copy would not fit.
    let before = std::fs::read(&cut).unwrap();
    let mut left = |_: &Path| -> std::io::Result<u64> { Ok(cut_bytes - 1) };
    let e = resume(
        &cut,
        &cut,
        &ResumeOptions::default(),
        Control {
            free_space: Some(&mut left),
            ..Control::default()
        },
    )
    .unwrap_err();
    assert!(
        // (the copy and the reserve to finish it: fs::disk's finish_reserve)
        matches!(e, RunError::NoRoom { need, .. } if need > cut_bytes),
        "{e:?}"
    );
    let msg = e.to_string();
    assert!(msg.contains("--out on another disk"), "{msg}");
    assert_eq!(std::fs::read(&cut).unwrap(), before);
    let mut tmpname = cut.file_name().unwrap().to_os_string();
    tmpname.push(".resume-tmp");
    assert!(!cut.with_file_name(tmpname).exists());
    // Resumed on a disk with room, it continues from the stop itself (its last
    // checkpoint) to the same collisions and snapshots as the run with room.
    let out = tmp("tight-resumed.mcap");
    let r = resume(&cut, &out, &ResumeOptions::default(), Control::default()).unwrap();
    assert_eq!(r.stop_reason, StopReason::Time);
    assert_eq!(observations(&out), observations(&full));
    for p in [&full, &cut, &out] {
        std::fs::remove_file(p).unwrap();
    }
}

#[test]
fn resume_errors_are_clear() {
    // A log without any checkpoint.
    let path = tmp("nocheckpoint.mcap");
    let meta = test_run_metadata(1);
    let mut w = LogWriter::create(
        &path,
        WriterOptions::default(),
        &meta.to_map(),
        WriterPosition::default(),
    )
    .unwrap();
    w.finish(&BTreeMap::new()).unwrap();
    let out = tmp("never.mcap");
    let e = resume(&path, &out, &ResumeOptions::default(), Control::default()).unwrap_err();
    assert!(
        matches!(e, RunError::Read(ReadError::NoCheckpoint { .. })),
        "{e}"
    );
    assert!(e.to_string().contains("no complete /checkpoint"), "{e}");
    assert!(!out.exists());

    // A stop before the checkpoint.
    let system = system(100, 0.3, false, false, 2);
    run(
        &spec(system, Stop::Time(3.0), log_opts()),
        &path,
        Control::default(),
    )
    .unwrap();
    let e = resume(
        &path,
        &out,
        &ResumeOptions {
            stop: Some(Stop::Time(1.0)),
        },
        Control::default(),
    )
    .unwrap_err();
    assert!(e.to_string().contains("stop.time"), "{e}");
    // A stop time that would write more than 10⁹ records (a mistyped exponent):
    // the smallest interval, thermo's 0.5, names the latest stop time allowed.
    for until in [1e12, 3.0 + 0.5e9 * (1.0 + 1e-9)] {
        let e = resume(
            &path,
            &out,
            &ResumeOptions {
                stop: Some(Stop::Time(until)),
            },
            Control::default(),
        )
        .unwrap_err();
        let text = e.to_string();
        assert!(
            text.contains("stop.time")
                && text.contains("records")
                && text.contains("log.thermo_interval")
                && text.contains("the latest stop time is 500000003"),
            "{text}"
        );
        assert!(!out.exists());
    }
    // Exactly 10⁹ records is allowed: the resume starts (and stops at once on
    // the raised stop flag, with its log finished).
    let stop = std::sync::atomic::AtomicBool::new(true);
    let s = resume(
        &path,
        &out,
        &ResumeOptions {
            stop: Some(Stop::Time(3.0 + 0.5e9)),
        },
        Control {
            stop: Some(&stop),
            ..Control::default()
        },
    )
    .unwrap();
    assert_eq!(s.stop_reason, StopReason::Interrupted);
    std::fs::remove_file(&out).unwrap();
    // A missing file.
    let e = resume(
        &tmp("missing.mcap"),
        &out,
        &ResumeOptions::default(),
        Control::default(),
    )
    .unwrap_err();
    assert!(e.to_string().contains("cannot read log"), "{e}");
    std::fs::remove_file(&path).unwrap();
}
