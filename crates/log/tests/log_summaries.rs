//! `scan`, `scan_indexed`, `scan_observed` and `last_checkpoint` agree with each
//! other and with what the test wrote.

mod log_common;
use log_common::*;

// ---------------------------------------------------------------------------
// Summaries: scan, scan_indexed, last_checkpoint
// ---------------------------------------------------------------------------

fn check_info(w: &Written, info: &carom_log::LogInfo, scene: bool) {
    assert_eq!(info.run, w.meta);
    assert_eq!(info.summary.as_ref(), Some(&w.summary));
    assert_eq!(info.end, LogEnd::Complete);
    assert_eq!(info.channels, [true, true, true, true, scene]);
    for (ch, topic) in TOPICS.iter().enumerate() {
        assert_eq!(info.messages[ch], w.messages(ch), "{topic}");
    }
    assert_eq!(info.logged_collisions, w.logged().len() as u64);
    assert_eq!(info.file_bytes, w.file_bytes);
    // Time spans from the messages themselves (exact), scene from its log times.
    let span = |f: &dyn Fn(&Item) -> bool| {
        let t: Vec<f64> = w.items.iter().filter(|i| f(i)).map(Item::time).collect();
        (!t.is_empty()).then(|| (t[0], t[t.len() - 1]))
    };
    let exact = |a: Option<(f64, f64)>, b: Option<(f64, f64)>| {
        a.map(|(x, y)| (x.to_bits(), y.to_bits())) == b.map(|(x, y)| (x.to_bits(), y.to_bits()))
    };
    assert!(exact(
        info.time_span[CH_COLLISIONS],
        span(&|i| matches!(i, Item::Collision(_)))
    ));
    assert!(exact(
        info.time_span[CH_SNAPSHOT],
        span(&|i| matches!(i, Item::Snapshot(_)))
    ));
    assert!(exact(
        info.time_span[CH_THERMO],
        span(&|i| matches!(i, Item::Thermo(_)))
    ));
    assert!(exact(
        info.time_span[CH_CHECKPOINT],
        span(&|i| matches!(i, Item::Checkpoint(_)))
    ));
    match span(&|i| matches!(i, Item::Scene(_))) {
        Some((a, b)) => {
            let (x, y) = info.time_span[CH_SCENE].unwrap();
            assert!((x - a).abs() < 1e-9 && (y - b).abs() < 1e-9, "{x} {y}");
        }
        None => assert_eq!(info.time_span[CH_SCENE], None),
    }
    let last_cp = w.of(CH_CHECKPOINT).last().unwrap().time();
    assert_eq!(info.last_checkpoint_time, Some(last_cp));
    let thermo = w.of(CH_THERMO);
    let counts = |i: &Item| match i {
        Item::Thermo(t) => (t.time, t.pair_collisions, t.wall_collisions),
        _ => unreachable!(),
    };
    assert_eq!(
        info.thermo_counts,
        Some([counts(&thermo[0]), counts(thermo.last().unwrap())])
    );
    if let Some(Item::Thermo(t)) = w.items.iter().rev().nth(1) {
        // The final thermo: the run's counts.
        let [_, (_, p, wl)] = info.thermo_counts.unwrap();
        assert_eq!((p, wl), (w.pair, w.wall));
        assert_eq!((t.pair_collisions, t.wall_collisions), (p, wl));
    }
}

/// `scan` and `scan_indexed` agree with each other and with what was written,
/// over several chunks; each channel's span is that of its own messages (the
/// last snapshot at 5/3 and the first scene frame at 1/2, whose nanoseconds
/// are and are not exact, the run ending after its last thermo record).
#[test]
fn scan_and_the_index_agree_with_what_was_written() {
    for scene in [false, true] {
        let w = write_log(
            "scan",
            Plan {
                detail: CollisionDetail::Compact,
                scene,
                t_end: 1.9,
                final_thermo: scene,
                chunk_size: 8 << 10,
                compression: Compression::None,
                ..Plan::default()
            },
        );
        assert!(chunks(&w.bytes()).len() > 2);
        let info = scan(&w.path).unwrap();
        check_info(&w, &info, scene);
        let indexed = scan_indexed(&w.path).unwrap().expect("an index");
        check_info(&w, &indexed, scene);
        assert_eq!(info, indexed);
    }
}

/// `scan_observed` reports progress that only grows, ending at the file's size.
#[test]
fn scan_reports_progress_up_to_the_whole_file() {
    let w = write_log(
        "progress",
        Plan {
            compression: Compression::None,
            ..Plan::default()
        },
    );
    let mut seen: Vec<ReadProgress> = Vec::new();
    scan_observed(&w.path, &mut |p| seen.push(p)).unwrap();
    assert!(seen.len() >= 2, "{seen:?}");
    assert!(seen.windows(2).all(|p| p[0].bytes_read <= p[1].bytes_read));
    assert!(seen.iter().all(|p| p.file_bytes == w.file_bytes));
    assert!(seen[0].bytes_read > 0 && seen[0].bytes_read < w.file_bytes);
    assert_eq!(seen.last().unwrap().bytes_read, w.file_bytes);
    assert_eq!(seen.last().unwrap().fraction(), 1.0);

    // The reader's own progress: some of the file after opening, all at the end.
    let mut r = open(&w.path);
    let p = r.progress();
    assert!(p.bytes_read > 0 && p.bytes_read < w.file_bytes, "{p:?}");
    let mut shown = 0;
    assert_eq!(r.progress_since(&mut shown), Some(p));
    assert_eq!(shown, p.bytes_read);
    assert_eq!(r.progress_since(&mut shown), None);
    while r.next_raw().unwrap().is_some() {}
    assert_eq!(r.progress().bytes_read, w.file_bytes);
    assert_eq!(
        r.progress_since(&mut shown).map(|p| p.bytes_read),
        Some(w.file_bytes)
    );
}

#[test]
fn the_fraction_read_is_bytes_over_size_at_most_one() {
    let f = |bytes_read, file_bytes| {
        ReadProgress {
            bytes_read,
            file_bytes,
        }
        .fraction()
    };
    assert_eq!(f(0, 0), 1.0);
    assert_eq!(f(1, 4), 0.25);
    assert_eq!(f(3, 4), 0.75);
    assert_eq!(f(0, 4), 0.0);
    assert_eq!(f(5, 4), 1.0);
}

/// The last checkpoint and the number of messages up to it.
#[test]
fn the_last_checkpoint_is_the_one_written_last() {
    let w = write_log(
        "lastcp",
        Plan {
            scene: true,
            ..Plan::default()
        },
    );
    let (cp, prefix, run) = last_checkpoint(&w.path).unwrap();
    match w.of(CH_CHECKPOINT).last().unwrap() {
        Item::Checkpoint(want) => assert_eq!(&cp, want.as_ref()),
        _ => unreachable!(),
    }
    let at = w
        .raw
        .iter()
        .rposition(|r| r.channel == CH_CHECKPOINT)
        .unwrap();
    assert_eq!(prefix, at as u64 + 1);
    assert_eq!(run, w.meta);
}
