//! The writer: flushes (a crash loses at most what came after the last flush), a
//! dropped writer, options, stats, I/O errors.

mod log_common;
use log_common::*;

// ---------------------------------------------------------------------------
// The writer
// ---------------------------------------------------------------------------

fn small_meta() -> BTreeMap<String, String> {
    RunMetadata {
        log_format: LOG_FORMAT_VERSION.into(),
        carom_version: "0.0.0-test".into(),
        config: "{}".into(),
        seed: 1,
        start_time: "2026-11-26T00:00:00.000Z".into(),
        n_discs: 2,
        stop: Stop::Collisions(10),
        max_time_without_collision: None,
        log: LogOptions::default(),
        resumed_from: None,
        resumed_at: None,
        run_facts: None,
    }
    .to_map()
}

fn thermo_at(t: f64) -> Thermo {
    Thermo {
        time: t,
        kinetic_energy: 1.5,
        temperature: 0.75,
        collisions: 3,
        pair_collisions: 2,
        wall_collisions: 1,
        energy_lost: 0.0,
        virial_sum: 0.5,
        wall_impulse: 0.25,
        pressure: None,
        z: None,
        collision_rate: None,
        ..Default::default()
    }
}

/// The thermo records a copy of the file taken now holds (none if it cannot be
/// read at all).
fn thermo_on_disk(path: &Path) -> usize {
    let bytes = std::fs::read(path).unwrap();
    let Ok(mut r) = reader(bytes, false) else {
        return 0;
    };
    r.thermo().filter(Result::is_ok).count()
}

fn inline(flush_every: Duration) -> WriterOptions {
    WriterOptions {
        background: false,
        flush_every,
        ..WriterOptions::default()
    }
}

/// A killed run loses at most what came after the last flush: an explicit flush
/// puts everything so far on disk, and nothing is flushed before `flush_every`.
#[test]
fn a_crash_loses_at_most_what_came_after_the_last_flush() {
    let path = tmp("flush");
    let hour = Duration::from_secs(3600);
    let mut w = LogWriter::create(&path, inline(hour), &small_meta(), Default::default()).unwrap();
    assert_eq!(w.path(), path.as_path());
    w.write_thermo(&thermo_at(0.5)).unwrap();
    w.maybe_flush().unwrap();
    assert_eq!(thermo_on_disk(&path), 0, "flushed before flush_every");
    w.flush().unwrap();
    assert_eq!(thermo_on_disk(&path), 1);
    w.write_thermo(&thermo_at(1.5)).unwrap();
    w.write_thermo(&thermo_at(2.5)).unwrap();
    w.maybe_flush().unwrap();
    assert_eq!(thermo_on_disk(&path), 1, "flushed before flush_every");
    w.flush().unwrap();
    assert_eq!(thermo_on_disk(&path), 3);
    drop(w);
    std::fs::remove_file(&path).unwrap();
}

/// With `flush_every` = 0 every message is on disk at once; otherwise, inline,
/// `maybe_flush` flushes once the time has passed, and a writer thread by itself.
#[test]
fn flushes_follow_flush_every() {
    let path = tmp("flush0");
    let mut w = LogWriter::create(
        &path,
        inline(Duration::ZERO),
        &small_meta(),
        Default::default(),
    )
    .unwrap();
    w.write_thermo(&thermo_at(0.5)).unwrap();
    assert_eq!(thermo_on_disk(&path), 1);
    drop(w);

    let step = Duration::from_millis(150);
    let mut w = LogWriter::create(&path, inline(step), &small_meta(), Default::default()).unwrap();
    w.write_thermo(&thermo_at(0.5)).unwrap();
    std::thread::sleep(step + Duration::from_millis(50));
    w.maybe_flush().unwrap();
    assert_eq!(thermo_on_disk(&path), 1);
    drop(w);

    let mut w = LogWriter::create(
        &path,
        WriterOptions {
            background: true,
            flush_every: Duration::from_millis(50),
            ..WriterOptions::default()
        },
        &small_meta(),
        Default::default(),
    )
    .unwrap();
    w.write_thermo(&thermo_at(0.5)).unwrap();
    let mut on_disk = 0;
    for _ in 0..100 {
        std::thread::sleep(Duration::from_millis(20));
        on_disk = thermo_on_disk(&path);
        if on_disk == 1 {
            break;
        }
    }
    assert_eq!(on_disk, 1, "the writer thread flushes by itself");
    drop(w);
    std::fs::remove_file(&path).unwrap();
}

/// Dropping a writer without finishing still ends the file properly, without a
/// summary; on a writer thread too, by the time the drop returns (here with
/// messages still queued for the thread when the writer is dropped).
#[test]
fn a_dropped_writer_leaves_a_finished_file() {
    // 256 KiB of text that compresses, but not to nothing.
    let mut x = 1u64;
    let big: Vec<u8> = (0..256 << 10)
        .map(|_| {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            b"0123456789abcdef"[(x >> 60) as usize]
        })
        .collect();
    for background in [false, true] {
        let path = tmp("drop");
        let mut w = LogWriter::create(
            &path,
            WriterOptions {
                background,
                ..WriterOptions::default()
            },
            &small_meta(),
            Default::default(),
        )
        .unwrap();
        for k in 0..12 {
            w.copy_message(CH_THERMO, k, 1000 * k as u64, 1000 * k as u64, &big)
                .unwrap();
        }
        drop(w);
        // The file as it is the moment the drop returns.
        let bytes = std::fs::read(&path).unwrap();
        let mut r = reader(bytes, false).unwrap();
        let mut n = 0;
        while let Some(m) = r.next_raw().unwrap() {
            assert_eq!((m.sequence, m.data.len()), (n, big.len()));
            n += 1;
        }
        assert_eq!(n, 12);
        assert_eq!(r.end(), &LogEnd::Complete);
        assert_eq!(r.summary().unwrap(), None);
        std::fs::remove_file(&path).unwrap();
    }
}

/// Options in force, stats, the debug form, and what `finish` returns.
#[test]
fn the_writer_reports_its_options_and_what_it_sent() {
    for background in [false, true] {
        let path = tmp("stats");
        let opts = WriterOptions {
            collision_every: 0,
            batch_size: 0,
            background,
            ..WriterOptions::default()
        };
        let position = WriterPosition {
            next_ordinal: 7,
            logged_collisions: 3,
            next_sequence: [1, 2, 3, 4],
        };
        let mut w = LogWriter::create(&path, opts.clone(), &small_meta(), position).unwrap();
        assert_eq!(
            w.options(),
            &WriterOptions {
                collision_every: 1,
                batch_size: 1,
                ..opts
            }
        );
        assert!(format!("{w:?}").contains("LogWriter"));
        let s = w.stats();
        assert_eq!((s.next_ordinal, s.logged_collisions), (7, 3));
        assert_eq!(s.messages, [0; N_CHANNELS]);
        let th = thermo_at(0.25);
        w.write_thermo(&th).unwrap();
        w.write_thermo(&th).unwrap();
        let s = w.stats();
        assert_eq!(s.messages, [0, 0, 2, 0, 0]);
        assert_eq!(
            s.largest_message,
            serde_json::to_vec(&th).unwrap().len() as u64
        );
        // A copied message: same channel, sequence, times and bytes.
        let data = serde_json::to_vec(&thermo_at(0.75)).unwrap();
        w.copy_message(CH_THERMO, 41, 750_000_000, 750_000_001, &data)
            .unwrap();
        assert_eq!(w.stats().messages, [0, 0, 3, 0, 0]);
        let size = w.close().unwrap();
        assert_eq!(size, std::fs::metadata(&path).unwrap().len());
        let mut r = open(&path);
        let mut seen = Vec::new();
        while let Some(m) = r.next_raw().unwrap() {
            seen.push((
                m.channel,
                m.sequence,
                m.log_time,
                m.publish_time,
                m.data.to_vec(),
            ));
        }
        assert_eq!(seen.len(), 3);
        assert_eq!(
            (seen[0].0, seen[0].1, seen[0].2),
            (CH_THERMO, 3, 250_000_000)
        );
        assert_eq!(seen[1].1, 4);
        assert_eq!(seen[2], (CH_THERMO, 41, 750_000_000, 750_000_001, data));
        // Once closed, writing fails.
        let e = w.write_thermo(&th).unwrap_err();
        assert!(matches!(e, WriteError::Finished(_)), "{e:?}");
        assert!(matches!(w.close(), Err(WriteError::Finished(_))));
        std::fs::remove_file(&path).unwrap();
    }
}

/// A write error is the operating system's error (a full disk says so).
#[test]
fn a_full_disk_is_reported_as_such() {
    let full = Path::new("/dev/full");
    if !full.exists() {
        return;
    }
    for background in [false, true] {
        let e = LogWriter::create(
            full,
            WriterOptions {
                background,
                ..WriterOptions::default()
            },
            &small_meta(),
            Default::default(),
        )
        .unwrap_err();
        assert!(
            matches!(&e, WriteError::Io { source, .. } if source.kind() == std::io::ErrorKind::StorageFull),
            "{e:?}"
        );
    }
}

/// A disk that fills while the run is writing: the error the caller gets is the
/// operating system's ("File too large", EFBIG), from the writer thread or inline,
/// and every later call says the log is finished. The disk is made to fill with a
/// file-size limit (`ulimit -f`, SIGXFSZ ignored so that the write fails instead
/// of killing the process) on a child process, this test binary run again.
#[cfg(unix)]
#[test]
fn a_disk_that_fills_mid_run_reports_the_os_error() {
    const CHILD: &str = "CAROM_IO_FSIZE_CHILD";
    const LIMIT_KIB: u64 = 64;
    if let Some(dir) = std::env::var_os(CHILD) {
        for background in [false, true] {
            let path = Path::new(&dir).join(format!("fills-{background}.mcap"));
            let opts = WriterOptions {
                background,
                compression: Compression::None,
                chunk_size: 4 << 10,
                flush_every: Duration::ZERO,
                ..WriterOptions::default()
            };
            let mut w = LogWriter::create(&path, opts, &small_meta(), Default::default())
                .expect("the header fits under the limit");
            // Each thermo record takes about 300 bytes: the limit is reached after
            // a few hundred, long before the 10⁵ offered.
            let (k, e) = (0..100_000)
                .find_map(|k| w.write_thermo(&thermo_at(k as f64)).err().map(|e| (k, e)))
                .expect("a write beyond the file-size limit fails");
            let shown = e.to_string();
            assert!(
                matches!(e, WriteError::Io { .. } | WriteError::Mcap { .. })
                    && shown.contains("too large"),
                "background {background}: {e:?} ({shown})"
            );
            // Nothing flushed is lost: every message was flushed when written, so the
            // records before the failing one are on disk, less, with the writer
            // thread, the queue (at most 8 messages, docs/log-format.md) and the one
            // being written when the limit was hit.
            let kept = thermo_on_disk(&path);
            let lost_at_most = if background { 9 } else { 0 };
            assert!(
                kept + lost_at_most >= k,
                "failed at record {k}, {kept} on disk"
            );
            let later = w.write_thermo(&thermo_at(0.0)).unwrap_err();
            assert!(matches!(later, WriteError::Finished(_)), "{later:?}");
            println!("carom-log child: background {background} failed as expected");
        }
        return;
    }
    let dir = tmp("fills-dir");
    std::fs::create_dir_all(&dir).unwrap();
    let out = std::process::Command::new("sh")
        .arg("-c")
        .arg(format!(
            r#"trap '' XFSZ; ulimit -f {}; exec "$0" "$@""#,
            LIMIT_KIB * 2
        ))
        .arg(std::env::current_exe().unwrap())
        .args(["--exact", "a_disk_that_fills_mid_run_reports_the_os_error"])
        .args(["--nocapture", "--test-threads", "1"])
        .env(CHILD, &dir)
        .output()
        .expect("sh runs");
    std::fs::remove_dir_all(&dir).unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success() && stdout.matches("failed as expected").count() == 2,
        "child: {}\n{stdout}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The documented defaults and the mapping of the user's log options.
#[test]
fn writer_options_follow_the_log_options() {
    let d = WriterOptions::default();
    assert_eq!(d.compression, Compression::Zstd);
    assert_eq!(
        d.compression_level, -1,
        "docs/performance.md: zstd level −1"
    );
    assert_eq!(d.chunk_size, 1 << 20, "docs/log-format.md: 1 MiB chunks");
    assert_eq!(d.batch_size, 4096, "docs/log-format.md: batches of 4096");
    assert_eq!(d.flush_every, Duration::from_secs(1));
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    assert_eq!(d.background, cores > 1);
    let o = |f: &dyn Fn(&mut LogOptions)| {
        let mut l = LogOptions::default();
        f(&mut l);
        WriterOptions::from_log_options(&l)
    };
    let w = o(&|l| {
        l.collisions = false;
        l.collision_every = 0;
        l.compression = Compression::Lz4;
        l.flush_seconds = 2.5;
    });
    assert!(!w.collisions);
    assert_eq!(w.collision_every, 1);
    assert_eq!(w.compression, Compression::Lz4);
    assert_eq!(w.compression_level, 0);
    assert_eq!(w.flush_every, Duration::from_secs_f64(2.5));
    let w = o(&|l| {
        l.collision_every = 4;
        l.compression = Compression::None;
        l.flush_seconds = -1.0;
    });
    assert_eq!(w.collision_every, 4);
    assert_eq!(w.collision_detail, CollisionDetail::Full);
    assert_eq!(w.compression_level, 0);
    assert_eq!(w.flush_every, Duration::ZERO);
    for never in [f64::INFINITY, f64::NAN] {
        assert_eq!(
            o(&|l| l.flush_seconds = never).flush_every,
            Duration::from_secs(1_000_000_000)
        );
    }
    assert!(WriterOptions::needs_normals(Restitution::CentreOfMass(0.5)));
    assert!(!WriterOptions::needs_normals(Restitution::CentreOfMass(
        1.0
    )));
    assert!(!WriterOptions::needs_normals(Restitution::Elastic));
    assert!(!WriterOptions::needs_normals(Restitution::Normal(0.5)));
}

#[test]
fn the_log_end_warns_only_when_cut() {
    let t = LogEnd::Truncated {
        detail: "cut here".into(),
    };
    let w = t.warning().unwrap();
    assert!(w.contains("truncated") && w.contains("cut here"), "{w}");
    for e in [LogEnd::Reading, LogEnd::Complete, LogEnd::Failed] {
        assert_eq!(e.warning(), None);
    }
    let _ = (KIND_WALL, NO_DISC);
}
