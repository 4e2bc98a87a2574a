//! Files carom would not write (by hand with the `mcap` crate): wrong schemas and
//! encodings, foreign files, extra metadata; each refused with a clear error.

mod log_common;
use log_common::*;

// ---------------------------------------------------------------------------
// Files carom would not write
// ---------------------------------------------------------------------------

const SNAP_SCHEMA: &str = "carom_msgs/msg/Snapshot";

/// An MCAP file with `meta` as its `carom.run` record and the channels
/// (topic, schema name, schema encoding, message encoding), without messages.
fn foreign(meta: &BTreeMap<String, String>, channels: &[(&str, &str, &str, &str)]) -> Vec<u8> {
    foreign_bytes(meta, channels)
}

fn foreign_bytes(
    meta: &BTreeMap<String, String>,
    channels: &[(&str, &str, &str, &str)],
) -> Vec<u8> {
    let mut buf = Cursor::new(Vec::new());
    {
        let mut w = mcap::WriteOptions::new().create(&mut buf).unwrap();
        w.write_metadata(&mcap::records::Metadata {
            name: METADATA_RUN.into(),
            metadata: meta.clone(),
        })
        .unwrap();
        for (topic, schema, enc, msg) in channels {
            let sid = w.add_schema(schema, enc, b"").unwrap();
            w.add_channel(sid, topic, msg, &BTreeMap::new()).unwrap();
        }
        w.finish().unwrap();
    }
    buf.into_inner()
}

/// A carom topic with another schema, schema encoding or message encoding is
/// refused, each on its own.
#[test]
fn a_carom_topic_with_another_schema_or_encoding_is_refused() {
    let meta = write_log(
        "meta2",
        Plan {
            t_end: 0.1,
            ..Plan::default()
        },
    )
    .meta
    .to_map();
    let good = ("/snapshot", SNAP_SCHEMA, "ros2msg", "cdr");
    let mut r = reader(foreign_bytes(&meta, &[good]), false).unwrap();
    assert!(r.next_raw().unwrap().is_none());
    assert_eq!(r.channels_seen(), [false, true, false, false, false]);
    for bad in [
        ("/snapshot", "other/Snapshot", "ros2msg", "cdr"),
        ("/snapshot", SNAP_SCHEMA, "jsonschema", "cdr"),
        ("/snapshot", SNAP_SCHEMA, "ros2msg", "json"),
    ] {
        let mut r = reader(foreign_bytes(&meta, &[bad]), false).unwrap();
        let e = r.next_raw().unwrap_err();
        assert!(
            matches!(
                e,
                ReadError::WrongSchema {
                    topic: "/snapshot",
                    ..
                }
            ),
            "{bad:?}: {e:?}"
        );
        assert_eq!(r.end(), &LogEnd::Failed);
    }
}

/// The first record must be the `carom.run` metadata.
#[test]
fn a_file_without_carom_run_metadata_first_is_not_a_carom_log() {
    let meta = write_log(
        "meta3",
        Plan {
            t_end: 0.1,
            ..Plan::default()
        },
    )
    .meta
    .to_map();
    let mut buf = Cursor::new(Vec::new());
    {
        let mut w = mcap::WriteOptions::new().create(&mut buf).unwrap();
        w.write_metadata(&mcap::records::Metadata {
            name: "other.run".into(),
            metadata: meta.clone(),
        })
        .unwrap();
        w.finish().unwrap();
    }
    let e = reader(buf.into_inner(), false).unwrap_err();
    assert!(matches!(e, ReadError::NotCarom { .. }), "{e:?}");
    let e = reader(b"not an mcap file at all".to_vec(), false).unwrap_err();
    assert!(matches!(e, ReadError::NotCarom { .. }), "{e:?}");
    // An MCAP file that ends before any record.
    let e = reader(mcap::MAGIC.to_vec(), false).unwrap_err();
    assert!(matches!(e, ReadError::NotCarom { .. }), "{e:?}");
}

/// Only the metadata record named `carom.summary` is the summary, wherever
/// another one comes.
#[test]
fn only_the_carom_summary_record_is_the_summary() {
    let path = tmp("summary-last");
    let w = write_log(
        "meta4",
        Plan {
            t_end: 0.1,
            ..Plan::default()
        },
    );
    let mut writer = LogWriter::create(
        &path,
        WriterOptions {
            background: false,
            ..WriterOptions::default()
        },
        &w.meta.to_map(),
        WriterPosition::default(),
    )
    .unwrap();
    writer
        .write_metadata(METADATA_SUMMARY, &w.summary_map)
        .unwrap();
    let mut other = BTreeMap::new();
    other.insert("note".to_string(), "after the summary".to_string());
    writer.write_metadata("notes", &other).unwrap();
    let size = writer.close().unwrap();
    assert_eq!(size, std::fs::metadata(&path).unwrap().len());
    let mut r = open(&path);
    while r.next_raw().unwrap().is_some() {}
    assert_eq!(r.summary().unwrap(), Some(w.summary.clone()));
    std::fs::remove_file(&path).unwrap();
}

/// The index of a damaged summary section is not used: `scan_indexed` says
/// `None` (for the full scan to find the damage) rather than fail or panic.
#[test]
fn a_damaged_index_is_left_to_the_full_scan() {
    let w = write_log(
        "index",
        Plan {
            chunk_size: 16 << 10,
            ..Plan::default()
        },
    );
    let bytes = w.bytes();
    let recs = records(&bytes);
    // The footer's summary CRC set to 0 (= not computed), so the summary reader
    // takes the edited section.
    let footer = recs.last().unwrap();
    assert_eq!(footer.0, 0x02);
    let crc_at = footer.1 + 9 + 16;
    let path = tmp("index-damaged");
    let edit = |f: &dyn Fn(&mut Vec<u8>)| {
        let mut b = bytes.clone();
        b[crc_at..crc_at + 4].copy_from_slice(&[0; 4]);
        f(&mut b);
        std::fs::write(&path, &b).unwrap();
        scan_indexed(&path)
    };
    // Unedited (but for the CRC): the index is used.
    assert!(edit(&|_| {}).unwrap().is_some());
    // The index of the carom.summary record (name after offset and length).
    let mi = recs
        .iter()
        .find(|r| {
            r.0 == OP_METADATA_INDEX
                && bytes[r.1 + 9 + 20..r.1 + r.2].starts_with(METADATA_SUMMARY.as_bytes())
        })
        .unwrap();
    let ci = recs.iter().find(|r| r.0 == OP_CHUNK_INDEX).unwrap();
    let put = |b: &mut Vec<u8>, at: usize, v: u64| b[at..at + 8].copy_from_slice(&v.to_le_bytes());
    // The summary metadata's length too short to hold a record.
    let len_at = mi.1 + 9 + 8;
    for short in [0, 5, 8] {
        assert_eq!(edit(&|b| put(b, len_at, short)).unwrap(), None, "{short}");
    }
    // Its offset beyond the end of the file.
    let off_at = mi.1 + 9;
    assert_eq!(
        edit(&|b| put(b, off_at, bytes.len() as u64 + 10)).unwrap(),
        None
    );
    // A chunk that starts beyond the end of the file.
    let cstart_at = ci.1 + 9 + 16;
    assert_eq!(
        edit(&|b| put(b, cstart_at, bytes.len() as u64 + 10)).unwrap(),
        None
    );
    // A cut file has no index.
    std::fs::write(&path, &bytes[..bytes.len() - 100]).unwrap();
    assert_eq!(scan_indexed(&path).unwrap(), None);
    std::fs::remove_file(&path).unwrap();
    assert!(recs.iter().any(|r| r.0 == OP_DATA_END));
    assert!(recs.iter().any(|r| r.0 == OP_METADATA));
}

/// A file with only some channels (written by another program): asking for a
/// channel it lacks is an error naming it, with no hint of truncation.
#[test]
fn a_missing_channel_in_a_whole_file_is_named() {
    let meta = write_log(
        "meta",
        Plan {
            t_end: 0.1,
            ..Plan::default()
        },
    )
    .meta
    .to_map();
    // Only /snapshot.
    let bytes = foreign(&meta, &[("/snapshot", SNAP_SCHEMA, "ros2msg", "cdr")]);
    let mut r = reader(bytes.clone(), false).unwrap();
    let got: Vec<_> = r.collisions().collect();
    assert_eq!(got.len(), 1);
    match &got[0] {
        Err(ReadError::MissingChannel { topic, hint, .. }) => {
            assert_eq!(*topic, "/collisions");
            assert_eq!(hint, "");
        }
        e => panic!("{e:?}"),
    }
    let mut r = reader(bytes.clone(), false).unwrap();
    assert_eq!(r.snapshots().count(), 0);
    let mut r = reader(bytes.clone(), false).unwrap();
    assert_eq!(r.events().count(), 0);
    // Only /collisions.
    let bytes = foreign(
        &meta,
        &[(
            "/collisions",
            "carom_msgs/msg/CollisionBatch",
            "ros2msg",
            "cdr",
        )],
    );
    let mut r = reader(bytes.clone(), false).unwrap();
    let got: Vec<_> = r.snapshots().collect();
    assert_eq!(got.len(), 1);
    assert!(
        matches!(
            &got[0],
            Err(ReadError::MissingChannel {
                topic: "/snapshot",
                ..
            })
        ),
        "{got:?}"
    );
    let mut r = reader(bytes.clone(), false).unwrap();
    assert_eq!(r.collisions().count(), 0);
    let mut r = reader(bytes, false).unwrap();
    assert_eq!(r.events().count(), 0);
}
