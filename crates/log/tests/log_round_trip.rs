//! Round trips of small logs through `LogWriter` and `LogReader`: full and compact
//! records, every k-th collision, a resumed writer position; every value compared
//! with what the test wrote, floats bit for bit.

mod log_common;
use log_common::*;

// ---------------------------------------------------------------------------
// Round trips
// ---------------------------------------------------------------------------

/// Everything of a full-record log reads back: each iterator, raw messages with
/// their sequences and times, the metadata, the counts.
#[test]
fn a_full_record_log_reads_back_exactly_what_was_written() {
    let w = write_log("full", Plan::default());
    let logged = w.logged();
    assert!(
        w.pair > 20 && w.wall > 5,
        "{} pair, {} wall",
        w.pair,
        w.wall
    );
    assert!(w.batches.iter().any(|b| b.len() == 1));
    assert!(w.batches.iter().any(|b| b.len() == w.options.batch_size));
    assert_eq!(logged.len() as u64, w.pair + w.wall);

    // Raw messages: channel, sequence, times, in file order; the reader's counters.
    let mut r = open(&w.path);
    assert_eq!(r.label(), w.path.display().to_string());
    assert!(format!("{r:?}").contains(&w.path.display().to_string()));
    assert_eq!(r.run(), &w.meta);
    assert_eq!(r.run_map(), &w.meta.to_map());
    assert_eq!(r.end(), &LogEnd::Reading);
    assert_eq!(r.summary().unwrap(), None);
    let mut k = 0;
    while let Some(m) = r.next_raw().unwrap() {
        assert_eq!(Raw::of(&m), w.raw[k], "raw message #{k}");
        k += 1;
        assert_eq!(r.messages_read(), k as u64);
    }
    assert_eq!(k, w.raw.len());
    assert_eq!(r.end(), &LogEnd::Complete);
    assert_eq!(r.end().warning(), None);
    assert_eq!(r.summary().unwrap(), Some(w.summary.clone()));
    assert_eq!(r.channels_seen(), [true, true, true, true, false]);
    assert!(!r.compact_collisions());
    // At the end, nothing more (and no error).
    assert!(r.next_raw().unwrap().is_none());
    assert!(r.next_message().unwrap().is_none());

    // Every collision, one at a time.
    let mut r = open(&w.path);
    let mut n = 0;
    for c in r.collisions() {
        let c = c.unwrap();
        assert!(n < logged.len(), "more collisions than written");
        check_collision(&c, &logged[n], false, n);
        n += 1;
    }
    assert_eq!(n, logged.len());
    assert_eq!(r.messages_read(), w.raw.len() as u64);

    // Each other channel on its own.
    for (ch, it) in [(CH_SNAPSHOT, 0), (CH_THERMO, 1), (CH_CHECKPOINT, 2)] {
        let want = w.of(ch);
        assert!(want.len() >= 2, "{}", TOPICS[ch]);
        let mut r = open(&w.path);
        let iter = match it {
            0 => r.snapshots(),
            1 => r.thermo(),
            _ => r.checkpoints(),
        };
        let mut n = 0;
        for m in iter {
            let m = m.unwrap();
            assert!(n < want.len(), "{}: more than written", TOPICS[ch]);
            check_message(&m, &want[n], false);
            n += 1;
        }
        assert_eq!(n, want.len(), "{}", TOPICS[ch]);
    }

    // All events in time order.
    let mut r = open(&w.path);
    assert_eq!(check_events(&mut r, &w, false), w.items.len());

    // Whole messages: the batches as batched.
    check_whole_messages(&w, false);
}

/// A compact log replays into the full records: velocities bit for bit, the
/// rest derived; scene frames are skipped by the decoding iterators and kept by
/// the raw ones.
#[test]
fn a_compact_log_with_scene_frames_replays_every_collision() {
    let w = write_log(
        "compact",
        Plan {
            detail: CollisionDetail::Compact,
            scene: true,
            compression: Compression::Lz4,
            batch_size: 9,
            ..Plan::default()
        },
    );
    let logged = w.logged();
    assert!(w.messages(CH_SCENE) >= 3);

    let mut r = open(&w.path);
    let mut n = 0;
    for c in r.collisions() {
        let c = c.unwrap();
        assert!(n < logged.len(), "more collisions than written");
        check_collision(&c, &logged[n], true, n);
        n += 1;
    }
    assert_eq!(n, logged.len());
    assert!(r.compact_collisions());
    assert_eq!(r.channels_seen(), [true; N_CHANNELS]);

    let mut r = open(&w.path);
    let scenes = w.messages(CH_SCENE) as usize;
    assert_eq!(check_events(&mut r, &w, true), w.items.len() - scenes);

    // Raw: the scene frames too, numbered by frame.
    let mut r = open(&w.path);
    let mut k = 0;
    while let Some(m) = r.next_raw().unwrap() {
        assert_eq!(Raw::of(&m), w.raw[k], "raw message #{k}");
        k += 1;
    }
    assert_eq!(k, w.raw.len());

    // Whole messages skip the scene.
    check_whole_messages(&w, true);

    // The snapshots alone, in a compact log with scene frames.
    let want = w.of(CH_SNAPSHOT);
    let mut r = open(&w.path);
    let got: Vec<LogMessage> = r.snapshots().map(Result::unwrap).collect();
    assert_eq!(got.len(), want.len());
    for (g, s) in got.iter().zip(&want) {
        check_message(g, s, true);
    }
}

/// A compact log whose first velocities come from its start checkpoint only (no
/// snapshot before the first collisions) replays from the checkpoint.
#[test]
fn a_compact_log_replays_from_a_checkpoint_without_a_snapshot() {
    let w = write_log(
        "compact-cp",
        Plan {
            detail: CollisionDetail::Compact,
            start_snapshot: false,
            compression: Compression::None,
            t_end: 0.3,
            ..Plan::default()
        },
    );
    let logged = w.logged();
    assert!(!logged.is_empty());
    assert_eq!(w.messages(CH_SNAPSHOT), 0);
    let mut r = open(&w.path);
    let mut n = 0;
    for c in r.collisions() {
        let c = c.unwrap();
        assert!(n < logged.len());
        check_collision(&c, &logged[n], true, n);
        n += 1;
    }
    assert_eq!(n, logged.len());
}

/// Every k-th collision: full records (compact needs every collision, whatever
/// the options ask), ordinals multiples of k, on a writer thread; the writer's
/// position carries over (ordinals, logged count, sequence numbers).
#[test]
fn every_kth_collision_from_a_resumed_position_on_a_writer_thread() {
    let position = WriterPosition {
        next_ordinal: 300,
        logged_collisions: 100,
        next_sequence: [5, 6, 7, 8],
    };
    let w = write_log(
        "every3",
        Plan {
            detail: CollisionDetail::Compact,
            every: 3,
            background: true,
            position,
            batch_size: 4,
            ..Plan::default()
        },
    );
    let logged = w.logged();
    assert!(logged.len() > 5);
    assert!(logged
        .iter()
        .all(|c| c.ordinal % 3 == 0 && c.ordinal >= 300));
    assert_eq!(logged[0].ordinal, 300);
    let mut r = open(&w.path);
    let mut k = 0;
    while let Some(m) = r.next_raw().unwrap() {
        assert_eq!(m.sequence, w.raw[k].sequence, "#{k}");
        assert_eq!(m.channel, w.raw[k].channel, "#{k}");
        k += 1;
    }
    let mut r = open(&w.path);
    assert_eq!(check_events(&mut r, &w, false), w.items.len());
    assert!(!r.compact_collisions());
    let (cp, _, _) = last_checkpoint(&w.path).unwrap();
    assert_eq!(cp.driver.logged_collisions, 100 + logged.len() as u64);
    assert_eq!(w.summary.logged_collisions, 100 + logged.len() as u64);
}

/// Without collisions: no `/collisions` message, the four channels still
/// defined, ordinals still counted.
#[test]
fn a_log_without_collisions_still_defines_its_channels() {
    let w = write_log(
        "nocoll",
        Plan {
            collisions: false,
            ..Plan::default()
        },
    );
    assert!(w.logged().is_empty());
    let mut r = open(&w.path);
    assert_eq!(r.collisions().count(), 0);
    assert_eq!(r.channels_seen(), [true, true, true, true, false]);
    let info = scan(&w.path).unwrap();
    assert_eq!(info.messages[CH_COLLISIONS], 0);
    assert_eq!(info.logged_collisions, 0);
    assert_eq!(info.time_span[CH_COLLISIONS], None);
    assert_eq!(info.channels, [true, true, true, true, false]);
}

/// `next_message` gives the collision batches as batched (each record checked,
/// `compact` as in [`check_collision`]) and every other message but the scene
/// frames in writing order.
fn check_whole_messages(w: &Written, compact: bool) {
    let mut r = open(&w.path);
    let (mut b, mut others) = (0, 0);
    let others_want: Vec<Item> = w
        .items
        .iter()
        .filter(|i| !matches!(i, Item::Collision(_) | Item::Scene(_)))
        .cloned()
        .collect();
    while let Some(m) = r.next_message().unwrap() {
        match m {
            LogMessage::Collisions(batch) => {
                assert!(b < w.batches.len());
                let want = &w.batches[b];
                assert_eq!(batch.len(), want.len(), "batch #{b}");
                for (e, c) in want.iter().enumerate() {
                    check_collision(&batch.get(e), c, compact, e);
                }
                b += 1;
            }
            m => {
                check_message(&m, &others_want[others], compact);
                others += 1;
            }
        }
    }
    assert_eq!((b, others), (w.batches.len(), others_want.len()));
}
