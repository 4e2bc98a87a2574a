//! Crash safety: a real child process writing a log is killed with SIGKILL
//! mid-run. Everything up to its last flush must be readable by carom's reader
//! (bit-identical to the engine's collisions) and by the Python `mcap` streaming
//! reader, and the run must resume from the file's last checkpoint to exactly the
//! log an uninterrupted run writes. The Python and `@mcap/core` parts skip when
//! their packages are missing, or fail when `CI` is set (tests/readers_common).
//!
//! The child is this test binary run again with `CAROM_CRASH_CHILD=<log path>`,
//! selecting only [`crash_child`] (`--exact mcap_crash::crash_child`), which then
//! runs "forever".

use crate::mcap_common::*;
use carom_engine::EngineParams;
use carom_log::CollisionRecord;
use carom_log::StopReason;
use carom_log::CH_CHECKPOINT;
use carom_log::{scan, scan_indexed, LogEnd, LogEvent, LogReader};
use carom_log::{Compression, LogOptions, Stop};
use carom_run::{resume, run, Control, ResumeOptions};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const CHILD_ENV: &str = "CAROM_CRASH_CHILD";

fn log_opts() -> LogOptions {
    LogOptions {
        collisions: true,
        collision_every: 1,
        collision_detail: Default::default(),
        snapshot_interval: Some(10.0),
        snapshot_schedule: None,
        thermo_interval: Some(2.0),
        checkpoint_interval: Some(20.0),
        scene_interval: None,
        compression: Compression::Zstd,
        flush_seconds: 0.05,
    }
}

fn crash_system() -> carom_engine::SystemSpec {
    system(400, 0.5, true, false, 77)
}

/// In the child: run until killed. In a normal test run: nothing.
#[test]
fn crash_child() {
    let Ok(path) = std::env::var(CHILD_ENV) else {
        return;
    };
    run(
        &spec(crash_system(), Stop::Time(1e9), log_opts()),
        Path::new(&path),
        Control::default(),
    )
    .unwrap();
    panic!("the child run should have been killed");
}

fn all_events(path: &Path) -> (Vec<LogEvent>, LogEnd) {
    let mut r = LogReader::open(path).unwrap();
    let v: Vec<_> = r.events().collect::<Result<_, _>>().unwrap();
    (v, r.end().clone())
}

fn collisions_of(events: &[LogEvent]) -> Vec<CollisionRecord> {
    events
        .iter()
        .filter_map(|e| match e {
            LogEvent::Collision(c) => Some(*c),
            _ => None,
        })
        .collect()
}

#[test]
fn sigkill_mid_run_leaves_a_readable_resumable_log() {
    let path = tmp("crash.mcap");
    let mut child = Command::new(std::env::current_exe().unwrap())
        .args([
            "--exact",
            "mcap_crash::crash_child",
            "--nocapture",
            "--test-threads=1",
        ])
        .env(CHILD_ENV, &path)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("child starts");
    // Wait until the child has flushed several checkpoints and many collisions,
    // reading the growing file as it is written.
    let start = Instant::now();
    let info = loop {
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "child made no progress"
        );
        assert!(child.try_wait().unwrap().is_none(), "child exited early");
        std::thread::sleep(Duration::from_millis(50));
        if let Ok(info) = scan(&path) {
            if info.messages[CH_CHECKPOINT] >= 12 && info.logged_collisions >= 200_000 {
                break info;
            }
        }
    };
    child.kill().expect("SIGKILL"); // Child::kill sends SIGKILL on Unix
    child.wait().unwrap();
    assert!(matches!(info.end, LogEnd::Truncated { .. }));

    // carom reads everything up to the last flush, and it is what the engine did.
    let info = scan(&path).unwrap();
    assert!(
        matches!(info.end, LogEnd::Truncated { .. }),
        "{:?}",
        info.end
    );
    let warning = info.end.warning().unwrap();
    assert!(warning.contains("truncated"), "{warning}");
    assert!(info.summary.is_none());
    // A cut log has no index to read instead.
    assert_eq!(scan_indexed(&path).unwrap(), None);
    let (events, end) = all_events(&path);
    assert!(matches!(end, LogEnd::Truncated { .. }));
    let logged = collisions_of(&events);
    assert_eq!(logged.len() as u64, info.logged_collisions);
    let t_last = logged.last().unwrap().time;
    // Observations come before collisions at the same instant: stop just after t_last.
    let (reference, _) =
        reference_collisions(&crash_system(), EngineParams::default(), t_last.next_up());
    assert!(reference.len() >= logged.len());
    for (k, (rec, ev)) in logged.iter().zip(&reference).enumerate() {
        let same = same_as_engine(rec, ev);
        assert!(same, "collision {k} differs: {rec:?} vs {ev:?}");
    }
    // Strict reading reports the cut as an error.
    let mut strict = LogReader::open_with(
        &path,
        carom_log::ReadOptions {
            strict: true,
            ..Default::default()
        },
    )
    .unwrap();
    let last = strict.collisions().last().unwrap();
    assert!(
        matches!(last, Err(carom_log::ReadError::Truncated { .. })),
        "{last:?}"
    );

    // The Python streaming reader reads the same messages before the cut.
    if let Some(py) = python() {
        let v = read_with_python(&py, &path, true);
        assert!(!v["error"].is_null(), "python sees the cut");
        let counts = &v["counts"];
        for (k, topic) in ["/collisions", "/snapshot", "/thermo", "/checkpoint"]
            .iter()
            .enumerate()
        {
            assert_eq!(
                counts[topic].as_u64().unwrap_or(0),
                info.messages[k],
                "{topic} messages"
            );
        }
        let py_collisions = v["collisions"].as_u64().unwrap();
        assert_eq!(py_collisions, info.logged_collisions);
    }

    // @mcap/core's stream reader (Foxglove's) reads the same messages and waits at
    // the cut, and `carom repair` makes it a complete log with those messages.
    if let Some(v) = node_read(&path) {
        assert_eq!(v["complete"], serde_json::Value::Bool(false), "{v}");
        for (k, topic) in ["/collisions", "/snapshot", "/thermo", "/checkpoint"]
            .iter()
            .enumerate()
        {
            let n = v["messages"][topic].as_u64().unwrap_or(0);
            assert_eq!(n, info.messages[k], "{topic} messages");
        }
    }
    let repaired = tmp("crash-repaired.mcap");
    let o = Command::new(env!("CARGO_BIN_EXE_carom"))
        .args([
            "repair",
            path.to_str().unwrap(),
            "-o",
            repaired.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (again, end) = all_events(&repaired);
    assert_eq!(end, LogEnd::Complete);
    assert_eq!(again, events);
    let whole = scan(&repaired).unwrap();
    assert_eq!(whole.messages, info.messages);
    if let Some(py) = python() {
        // The indexed (non-streaming) reader needs the summary section.
        let v = read_with_python(&py, &repaired, false);
        assert!(v["error"].is_null(), "{v}");
        assert_eq!(
            v["counts"]["/checkpoint"].as_u64(),
            Some(info.messages[CH_CHECKPOINT])
        );
    }

    // Resume from the last checkpoint in the file; it must give exactly the log of
    // an uninterrupted run to the same end time.
    let (cp, _, _) = carom_log::last_checkpoint(&path).unwrap();
    let t_cp = cp.engine.now;
    assert!((info.last_checkpoint_time.unwrap() - t_cp).abs() < 1e-6);
    let t_end = t_cp + 15.0;
    let resumed = tmp("crash-resumed.mcap");
    let s = resume(
        &path,
        &resumed,
        &ResumeOptions {
            stop: Some(Stop::Time(t_end)),
        },
        Control::default(),
    )
    .unwrap();
    assert_eq!(s.stop_reason, StopReason::Time);
    let uninterrupted = tmp("crash-reference.mcap");
    run(
        &spec(crash_system(), Stop::Time(t_end), log_opts()),
        &uninterrupted,
        Control::default(),
    )
    .unwrap();
    let r = LogReader::open(&resumed).unwrap();
    assert_eq!(r.run().resumed_at, Some(t_cp));
    let (a, end_a) = all_events(&resumed);
    let (b, end_b) = all_events(&uninterrupted);
    assert_eq!((end_a, end_b), (LogEnd::Complete, LogEnd::Complete));
    assert_eq!(collisions_of(&a), collisions_of(&b));
    let rest = |v: &[LogEvent]| -> Vec<LogEvent> {
        v.iter()
            .filter(|e| matches!(e, LogEvent::Snapshot(_) | LogEvent::Thermo(_)))
            .cloned()
            .collect()
    };
    assert_eq!(rest(&a), rest(&b));
    let last_state = |v: &[LogEvent]| match v.iter().rev().find_map(|e| match e {
        LogEvent::Checkpoint(c) => Some(c.clone()),
        _ => None,
    }) {
        Some(c) => (
            bits(&c.engine.positions),
            bits(&c.engine.velocities),
            c.engine.now,
        ),
        None => panic!("no checkpoint"),
    };
    assert_eq!(last_state(&a), last_state(&b));
    for p in [&path, &resumed, &uninterrupted] {
        std::fs::remove_file(p).unwrap();
    }
}
