//! Bad input never panics: thousands of seeded random corruptions of valid logs,
//! cuts at every offset, and files written by other programs each give either the
//! original content, a clean cut (warning), or an error naming the problem.

use crate::mcap_common::*;
use carom_log::RunMetadata;
use carom_log::{scan, scan_indexed, LogEnd, LogEvent, LogReader, ReadError, ReadOptions};
use carom_log::{Compression, LogOptions, Stop};
use carom_log::{LOG_FORMAT_VERSION, METADATA_RUN};
use carom_run::{run, Control};
use std::collections::BTreeMap;
use std::io::Cursor;
use std::panic::{catch_unwind, AssertUnwindSafe};

/// splitmix64: a seeded generator for the mutations.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// Everything a reader gets out of `bytes`: the events before the end or error,
/// how reading ended, and the error if any.
fn read_all(bytes: Vec<u8>, strict: bool) -> Result<(Vec<LogEvent>, LogEnd), ReadError> {
    let mut r = LogReader::new(
        Cursor::new(bytes),
        "mutant".into(),
        ReadOptions {
            strict,
            record_length_limit: None,
        },
    )?;
    let mut events = Vec::new();
    for e in r.events() {
        events.push(e?);
    }
    // The summary record, if reached, must parse or give an error (not panic).
    let _ = r.summary();
    Ok((events, r.end().clone()))
}

fn valid_log(compression: Compression) -> Vec<u8> {
    let out = tmp("fuzz-source.mcap");
    let log = LogOptions {
        collisions: true,
        collision_every: 1,
        collision_detail: Default::default(),
        snapshot_interval: Some(0.5),
        snapshot_schedule: None,
        thermo_interval: Some(0.25),
        checkpoint_interval: Some(1.0),
        scene_interval: None,
        compression,
        flush_seconds: 1.0,
    };
    run(
        &spec(system(60, 0.4, true, true, 4), Stop::Time(2.0), log),
        &out,
        Control::default(),
    )
    .unwrap();
    let bytes = std::fs::read(&out).unwrap();
    std::fs::remove_file(&out).unwrap();
    bytes
}

fn mutate(rng: &mut Rng, src: &[u8]) -> (Vec<u8>, String) {
    let mut b = src.to_vec();
    let n = b.len();
    let at = rng.below(n);
    let what = match rng.below(6) {
        0 => {
            let flips = 1 + rng.below(8);
            let mut at = Vec::new();
            for _ in 0..flips {
                let k = rng.below(n);
                b[k] ^= 1 << rng.below(8);
                at.push(k);
            }
            format!("{flips} bit flips at {at:?} of {n} bytes")
        }
        1 => {
            let len = (1 + rng.below(16)).min(n - at);
            for x in &mut b[at..at + len] {
                *x = rng.next() as u8;
            }
            format!("{len} random bytes at {at}")
        }
        2 => {
            b.truncate(at);
            format!("cut at {at}")
        }
        3 => {
            let len = (1 + rng.below(64)).min(n - at);
            b.drain(at..at + len);
            format!("{len} bytes deleted at {at}")
        }
        4 => {
            let len = 1 + rng.below(64);
            let ins: Vec<u8> = (0..len).map(|_| rng.next() as u8).collect();
            b.splice(at..at, ins);
            format!("{len} bytes inserted at {at}")
        }
        _ => {
            // A big length or count: write 0xff.. over 8 bytes.
            let len = 8.min(n - at);
            for x in &mut b[at..at + len] {
                *x = 0xff;
            }
            format!("0xff x{len} at {at}")
        }
    };
    (b, what)
}

#[test]
fn random_corruptions_never_panic_and_never_pass_silently() {
    let mut rng = Rng(0x5EED_CA20);
    let (mut complete_same, mut cut, mut errors) = (0, 0, 0);
    for compression in [Compression::Zstd, Compression::None] {
        let src = valid_log(compression);
        let (reference, end) = read_all(src.clone(), false).unwrap();
        assert_eq!(end, LogEnd::Complete);
        for trial in 0..1500 {
            let (bytes, what) = mutate(&mut rng, &src);
            let unchanged = bytes == src;
            let outcome = catch_unwind(AssertUnwindSafe(|| read_all(bytes, false)));
            let outcome = match outcome {
                Ok(o) => o,
                Err(_) => panic!("{compression:?} trial {trial}: reading panicked after {what}"),
            };
            match outcome {
                Ok((events, LogEnd::Complete)) => {
                    // Accepted as complete: then it must be the original content.
                    assert!(
                        events == reference,
                        "{compression:?} trial {trial}: {what} silently changed the content"
                    );
                    complete_same += 1;
                    let _ = unchanged;
                }
                Ok((events, LogEnd::Truncated { .. })) => {
                    // A cut (or damage read as one): what was read is a prefix.
                    assert!(events.len() <= reference.len());
                    let same_prefix = events.iter().zip(&reference).all(|(a, b)| a == b);
                    assert!(
                        same_prefix,
                        "{compression:?} trial {trial}: {what} changed content before the cut"
                    );
                    cut += 1;
                }
                Ok((events, LogEnd::Damaged { .. })) => {
                    // Damage after the last chunk: every message read, unchanged.
                    assert!(
                        events == reference,
                        "{compression:?} trial {trial}: {what} changed content (damaged end)"
                    );
                    complete_same += 1;
                }
                Ok((_, end)) => panic!("unexpected end {end:?}"),
                Err(e) => {
                    let msg = e.to_string();
                    assert!(msg.contains("mutant"), "errors name the file: {msg}");
                    errors += 1;
                }
            }
        }
    }
    eprintln!("corruptions: {complete_same} harmless, {cut} read as cut, {errors} errors");
    assert!(errors > 1000, "most corruptions are detected: {errors}");
}

#[test]
fn damaged_indexes_never_panic_and_agree_with_a_full_scan_when_both_read() {
    // scan_indexed trusts a finished log's index; damage must make it give up (or
    // fail with an error naming the file), never panic or ask for absurd memory,
    // and whatever it returns for a file that a full scan finds intact must equal
    // the scan.
    let mut rng = Rng(0x1DE7_5CA7);
    let path = tmp("index-mutant.mcap");
    let (mut agreed, mut gave_up, mut elsewhere) = (0, 0, 0);
    for compression in [Compression::Zstd, Compression::None] {
        let src = valid_log(compression);
        std::fs::write(&path, &src).unwrap();
        assert_eq!(
            scan_indexed(&path).unwrap(),
            Some(scan(&path).unwrap()),
            "{compression:?}: the intact log"
        );
        for trial in 0..400 {
            let (bytes, what) = mutate(&mut rng, &src);
            std::fs::write(&path, &bytes).unwrap();
            let indexed = catch_unwind(AssertUnwindSafe(|| scan_indexed(&path)))
                .unwrap_or_else(|_| panic!("{compression:?} trial {trial}: panicked after {what}"));
            match (indexed, scan(&path)) {
                (Ok(Some(i)), Ok(full)) if full.end == LogEnd::Complete => {
                    assert_eq!(i, full, "{compression:?} trial {trial}: {what}");
                    agreed += 1;
                }
                (Ok(None), _) => gave_up += 1,
                (Err(e), _) => assert!(e.to_string().contains("index-mutant"), "{e}"),
                // Damage outside what the index reads: found by the full read.
                (Ok(Some(_)), _) => elsewhere += 1,
            }
        }
    }
    std::fs::remove_file(&path).unwrap();
    eprintln!(
        "index mutants: {agreed} agreed with the scan, {gave_up} gave up, {elsewhere} damaged \
         elsewhere"
    );
    assert!(gave_up > 100 && elsewhere > 100, "{gave_up} {elsewhere}");
}

#[test]
fn cuts_at_any_offset_read_a_prefix() {
    let src = valid_log(Compression::Zstd);
    let (reference, _) = read_all(src.clone(), false).unwrap();
    let mut last_len = 0;
    for cut in (0..src.len()).step_by(src.len() / 400 + 1) {
        let bytes = src[..cut].to_vec();
        match read_all(bytes.clone(), false) {
            Ok((events, end)) => {
                assert!(
                    matches!(end, LogEnd::Truncated { .. }),
                    "cut {cut}: {end:?}"
                );
                assert_eq!(events[..], reference[..events.len()], "cut {cut}");
                assert!(events.len() >= last_len, "more bytes, no fewer events");
                last_len = events.len();
                // Strict mode reports the cut as an error.
                let strict = read_all(bytes, true);
                assert!(
                    matches!(strict, Err(ReadError::Truncated { .. })),
                    "cut {cut}: {strict:?}"
                );
            }
            Err(ReadError::NotCarom { problem, .. }) => {
                assert!(cut < 2000, "cut {cut} rejected late: {problem}");
            }
            Err(e) => panic!("cut {cut}: {e}"),
        }
    }
    assert!(last_len > reference.len() / 2);
}

fn run_metadata() -> BTreeMap<String, String> {
    RunMetadata {
        log_format: LOG_FORMAT_VERSION.into(),
        carom_version: "test".into(),
        config: "{}".into(),
        seed: 1,
        start_time: "2024-01-01T00:00:00.000Z".into(),
        n_discs: 1,
        stop: Stop::Time(1.0),
        max_time_without_collision: None,
        log: LogOptions::default(),
        resumed_from: None,
        resumed_at: None,
        run_facts: None,
    }
    .to_map()
}

/// An MCAP file written with the plain `mcap` writer: optional carom metadata,
/// then channels (topic, schema name, schema encoding, message encoding) with one
/// message each.
fn foreign(
    meta: Option<BTreeMap<String, String>>,
    channels: &[(&str, &str, &str, &str)],
) -> Vec<u8> {
    let mut w = mcap::Writer::new(Cursor::new(Vec::new())).unwrap();
    if let Some(m) = meta {
        w.write_metadata(&mcap::records::Metadata {
            name: METADATA_RUN.into(),
            metadata: m,
        })
        .unwrap();
    }
    for (k, (topic, schema, senc, menc)) in channels.iter().enumerate() {
        let sid = w.add_schema(schema, senc, b"int32 x").unwrap();
        let cid = w.add_channel(sid, topic, menc, &BTreeMap::new()).unwrap();
        w.write_to_known_channel(
            &mcap::records::MessageHeader {
                channel_id: cid,
                sequence: k as u32,
                log_time: 1,
                publish_time: 1,
            },
            &[0, 1, 0, 0, 7, 0, 0, 0],
        )
        .unwrap();
    }
    w.finish().unwrap();
    w.into_inner().into_inner()
}

fn open(bytes: Vec<u8>) -> Result<LogReader<Cursor<Vec<u8>>>, ReadError> {
    LogReader::new(
        Cursor::new(bytes),
        "foreign.mcap".into(),
        ReadOptions::default(),
    )
}

#[test]
fn files_from_other_programs_give_clear_errors() {
    let not_carom = |r: Result<LogReader<Cursor<Vec<u8>>>, ReadError>| match r {
        Err(e @ ReadError::NotCarom { .. }) => e.to_string(),
        Err(e) => panic!("expected NotCarom, got {e}"),
        Ok(_) => panic!("expected NotCarom, got a reader"),
    };
    let e = not_carom(open(Vec::new()));
    assert!(e.contains("foreign.mcap is not a carom log"), "{e}");
    let e = not_carom(open(b"time,x,y\n0,1,2\n".to_vec()));
    assert!(e.contains("not a readable MCAP file"), "{e}");
    let e = not_carom(open(foreign(
        None,
        &[("/imu", "sensor_msgs/msg/Imu", "ros2msg", "cdr")],
    )));
    assert!(e.contains("carom.run"), "{e}");

    // carom metadata but /collisions with another schema.
    let mut r = open(foreign(
        Some(run_metadata()),
        &[("/collisions", "other/msg/Thing", "ros2msg", "cdr")],
    ))
    .unwrap();
    let e = r.collisions().last().unwrap().unwrap_err();
    assert!(
        matches!(
            e,
            ReadError::WrongSchema {
                topic: "/collisions",
                ..
            }
        ),
        "{e}"
    );
    assert!(
        e.to_string().contains("carom_msgs/msg/CollisionBatch"),
        "{e}"
    );

    // carom metadata, an unknown extra channel (ignored), no /snapshot channel.
    let bytes = foreign(
        Some(run_metadata()),
        &[("/extra", "x/msg/X", "ros2msg", "cdr")],
    );
    let mut r = open(bytes.clone()).unwrap();
    let items: Vec<_> = r.snapshots().collect();
    assert_eq!(items.len(), 1);
    let e = items.into_iter().next().unwrap().unwrap_err();
    assert!(e.to_string().contains("has no /snapshot channel"), "{e}");
    let mut r = open(bytes).unwrap();
    assert!(matches!(
        r.collisions().next(),
        Some(Err(ReadError::MissingChannel {
            topic: "/collisions",
            ..
        }))
    ));

    // A carom log of a future format.
    let mut meta = run_metadata();
    meta.insert("log_format".into(), "9".into());
    match open(foreign(Some(meta), &[])) {
        Err(e @ ReadError::Metadata { .. }) => {
            assert!(e.to_string().contains("log_format"), "{e}")
        }
        other => panic!("{:?}", other.map(|_| ())),
    }
}
