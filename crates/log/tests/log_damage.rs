//! Files cut short or damaged: lenient and strict reading, errors after exactly
//! the messages before the damage, fallbacks of the summaries.

mod log_common;
use log_common::*;

// ---------------------------------------------------------------------------
// Cut and damaged files
// ---------------------------------------------------------------------------

/// A log flushed after every message group, several chunks.
fn chunked(name: &str, compression: Compression) -> Written {
    write_log(
        name,
        Plan {
            compression,
            flush_each: true,
            t_end: 1.0,
            ..Plan::default()
        },
    )
}

/// Messages in the chunks before chunk `k` (0-based): each flush closes one.
fn messages_before_chunk(w: &Written, k: usize) -> usize {
    if k == 0 {
        0
    } else {
        w.flushed_after[k - 1]
    }
}

/// A file cut short reads up to its last complete chunk: quietly
/// (`LogEnd::Truncated`) by default, as an error in strict mode.
#[test]
fn a_cut_file_reads_to_its_last_whole_chunk_or_fails_in_strict_mode() {
    let w = chunked("cut", Compression::Zstd);
    let bytes = w.bytes();
    let ch = chunks(&bytes);
    assert_eq!(ch.len(), w.flushed_after.len());
    for k in [1, 3] {
        // Cut in the middle of chunk k.
        let (start, len) = ch[k];
        let cut = bytes[..start + len / 2].to_vec();
        let before = messages_before_chunk(&w, k);
        // Lenient: everything before, then the end.
        let mut r = reader(cut.clone(), false).unwrap();
        let mut n = 0;
        while let Some(m) = r.next_raw().unwrap() {
            assert_eq!(m.sequence, w.raw[n].sequence);
            assert_eq!(m.channel, w.raw[n].channel);
            n += 1;
        }
        assert_eq!(n, before, "cut in chunk {k}");
        let LogEnd::Truncated { detail } = r.end().clone() else {
            panic!("{:?}", r.end())
        };
        let warning = r.end().warning().unwrap();
        assert!(warning.contains("truncated") && warning.contains(&detail));
        // The same through the decoding iterators: every event of those messages.
        let mut r = reader(cut.clone(), false).unwrap();
        let want = w
            .items
            .iter()
            .zip(&w.item_msg)
            .filter(|(i, &m)| m < before && !matches!(i, Item::Scene(_)))
            .count();
        let mut got = 0;
        for e in r.events() {
            e.unwrap();
            got += 1;
        }
        assert_eq!(got, want, "events before the cut in chunk {k}");
        // Strict: the same messages, then an error saying how many.
        let mut r = reader(cut.clone(), true).unwrap();
        let mut n = 0;
        let e = loop {
            match r.next_raw() {
                Ok(Some(_)) => n += 1,
                Ok(None) => panic!("a strict reader read to the end of a cut file"),
                Err(e) => break e,
            }
        };
        assert_eq!(n, before);
        assert!(
            matches!(e, ReadError::Truncated { messages, .. } if messages == before as u64),
            "{e:?}"
        );
        assert_eq!(r.end(), &LogEnd::Failed);
        // Nothing more after the end or the error.
        assert!(r.next_raw().unwrap().is_none());
    }
}

/// A cut before any chunk: no channel at all. Asking for one says it is missing
/// and why; all events are simply none.
#[test]
fn a_file_cut_before_its_channels_says_which_channel_is_missing() {
    let w = chunked("cut0", Compression::None);
    let bytes = w.bytes();
    let first = chunks(&bytes)[0].0;
    let cut = bytes[..first + 20].to_vec();
    let mut r = reader(cut.clone(), false).unwrap();
    assert_eq!(r.run(), &w.meta);
    assert_eq!(r.events().count(), 0);
    assert!(matches!(r.end(), LogEnd::Truncated { .. }));
    assert_eq!(r.channels_seen(), [false; N_CHANNELS]);
    for (name, topic) in [
        ("collisions", "/collisions"),
        ("snapshots", "/snapshot"),
        ("thermo", "/thermo"),
        ("checkpoints", "/checkpoint"),
    ] {
        let mut r = reader(cut.clone(), false).unwrap();
        let mut items: Vec<Result<(), ReadError>> = match name {
            "collisions" => r.collisions().map(|e| e.map(|_| ())).collect(),
            "snapshots" => r.snapshots().map(|e| e.map(|_| ())).collect(),
            "thermo" => r.thermo().map(|e| e.map(|_| ())).collect(),
            _ => r.checkpoints().map(|e| e.map(|_| ())).collect(),
        };
        assert_eq!(items.len(), 1, "{name}");
        match items.pop().unwrap() {
            Err(ReadError::MissingChannel { topic: t, hint, .. }) => {
                assert_eq!(t, topic);
                assert!(hint.contains("truncated"), "{hint}");
            }
            e => panic!("{name}: {e:?}"),
        }
    }
}

/// Damage inside a finished file is a `Corrupt` error after everything before
/// it, strict or not; `last_checkpoint` still finds the checkpoint before it.
#[test]
fn damage_in_a_finished_file_is_an_error_after_everything_before_it() {
    for compression in [Compression::None, Compression::Zstd] {
        let w = chunked("damage", compression);
        let bytes = w.bytes();
        let ch = chunks(&bytes);
        let k = ch.len() - 2;
        let before = messages_before_chunk(&w, k);
        let (start, len) = ch[k];
        let mut bad = bytes.clone();
        bad[start + len - 3] ^= 0x5a;
        for strict in [false, true] {
            let mut r = reader(bad.clone(), strict).unwrap();
            let mut n = 0;
            let e = loop {
                match r.next_raw() {
                    Ok(Some(m)) => {
                        assert_eq!(m.sequence, w.raw[n].sequence);
                        n += 1
                    }
                    Ok(None) => panic!("damage read to the end ({compression:?})"),
                    Err(e) => break e,
                }
            };
            assert_eq!(n, before);
            assert!(
                matches!(e, ReadError::Corrupt { messages, .. } if messages == before as u64),
                "{e:?}"
            );
            assert_eq!(r.end(), &LogEnd::Failed);
            assert_eq!(r.end().warning(), None);
        }
        // The events before the damage are what was written.
        let mut r = reader(bad.clone(), false).unwrap();
        let mut n = 0;
        let mut failed = false;
        for e in r.events() {
            match e {
                Ok(_) => n += 1,
                Err(e) => {
                    assert!(matches!(e, ReadError::Corrupt { .. }), "{e:?}");
                    failed = true;
                }
            }
        }
        assert!(failed);
        assert!(n > 0);
        // The last checkpoint before the damage.
        let path = tmp("damaged");
        std::fs::write(&path, &bad).unwrap();
        let (cp, prefix, _) = last_checkpoint(&path).unwrap();
        let at = w.raw[..before]
            .iter()
            .rposition(|r| r.channel == CH_CHECKPOINT)
            .unwrap();
        assert_eq!(prefix, at as u64 + 1);
        let cps = w.of(CH_CHECKPOINT);
        let nth = w.raw[..=at]
            .iter()
            .filter(|r| r.channel == CH_CHECKPOINT)
            .count();
        match &cps[nth - 1] {
            Item::Checkpoint(want) => assert_eq!(&cp, want.as_ref()),
            _ => unreachable!(),
        }
        // Damage in the first chunk, before any checkpoint: the damage is the error.
        let mut bad0 = bytes.clone();
        bad0[ch[0].0 + ch[0].1 - 3] ^= 0x5a;
        std::fs::write(&path, &bad0).unwrap();
        let e = last_checkpoint(&path).unwrap_err();
        assert!(matches!(e, ReadError::Corrupt { .. }), "{e:?}");
        std::fs::remove_file(&path).unwrap();
    }
}

/// Damage in the summary section (the index at the end, which repeats what the
/// data section said) is found after every message, and said to be there: a
/// warning (`LogEnd::Damaged`), not an error, since no message is lost.
#[test]
fn damage_in_the_summary_section_comes_after_every_message() {
    let w = write_log(
        "summary-damage",
        Plan {
            t_end: 0.5,
            ..Plan::default()
        },
    );
    let mut bytes = w.bytes();
    let recs = records(&bytes);
    let footer = *recs.last().unwrap();
    // Summary CRC 0 (= not computed): the damage is found by parsing the record.
    let crc_at = footer.1 + 9 + 16;
    bytes[crc_at..crc_at + 4].copy_from_slice(&[0; 4]);
    // The statistics record's per-channel counts claim more bytes than it has.
    let stats = recs.iter().find(|r| r.0 == 0x0B).unwrap();
    let map_len_at = stats.1 + 9 + 42;
    bytes[map_len_at..map_len_at + 4].copy_from_slice(&u32::MAX.to_le_bytes());
    let mut r = reader(bytes, false).unwrap();
    let mut n = 0;
    while r.next_raw().unwrap().is_some() {
        n += 1;
    }
    assert_eq!(n, w.raw.len());
    let LogEnd::Damaged { detail } = r.end().clone() else {
        panic!("{:?}", r.end())
    };
    assert!(detail.starts_with("malformed summary record"), "{detail}");
    assert!(r.end().warning().unwrap().contains("damaged"));
    // The summary metadata record came before the damage.
    assert_eq!(r.summary().unwrap(), Some(w.summary.clone()));
}

/// Reading hands every byte it takes to the MCAP reader; an I/O error is an error,
/// an interrupted read is retried.
#[test]
fn io_errors_end_reading_and_interrupted_reads_are_retried() {
    let w = write_log(
        "io",
        Plan {
            compression: Compression::None,
            t_end: 0.5,
            ..Plan::default()
        },
    );
    let bytes = w.bytes();
    for kind in [std::io::ErrorKind::Interrupted, std::io::ErrorKind::Other] {
        let fail = std::rc::Rc::new(std::cell::Cell::new(None));
        let src = Flaky {
            inner: Cursor::new(bytes.clone()),
            fail: fail.clone(),
        };
        let mut r = LogReader::new(src, "flaky".into(), ReadOptions::default()).unwrap();
        fail.set(Some(kind));
        let mut n = 0;
        let mut err = None;
        loop {
            match r.next_raw() {
                Ok(Some(_)) => n += 1,
                Ok(None) => break,
                Err(e) => {
                    err = Some(e);
                    break;
                }
            }
        }
        if kind == std::io::ErrorKind::Interrupted {
            assert!(err.is_none(), "{err:?}");
            assert_eq!(n, w.raw.len());
            assert_eq!(r.end(), &LogEnd::Complete);
        } else {
            let e = err.expect("an I/O error ends reading");
            assert!(
                matches!(&e, ReadError::Corrupt { detail, .. } if detail.contains("I/O")),
                "{e:?}"
            );
            assert!(n < w.raw.len());
        }
    }
}

/// A source that fails its next read once, with the error kind set.
struct Flaky {
    inner: Cursor<Vec<u8>>,
    fail: std::rc::Rc<std::cell::Cell<Option<std::io::ErrorKind>>>,
}

impl Read for Flaky {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        if let Some(kind) = self.fail.take() {
            return Err(std::io::Error::new(kind, "injected"));
        }
        self.inner.read(buf)
    }
}

impl Seek for Flaky {
    fn seek(&mut self, to: SeekFrom) -> std::io::Result<u64> {
        self.inner.seek(to)
    }
}

/// A record or decompressed chunk longer than the limit is refused (an error in a
/// finished file), and one within it is read.
#[test]
fn records_longer_than_the_limit_are_refused() {
    let w = write_log(
        "limit",
        Plan {
            compression: Compression::Zstd,
            t_end: 0.5,
            ..Plan::default()
        },
    );
    let bytes = w.bytes();
    let longest = records(&bytes).iter().map(|r| r.2).max().unwrap();
    let read = |limit| {
        let mut r = LogReader::new(
            Cursor::new(bytes.clone()),
            "limit".into(),
            ReadOptions {
                strict: false,
                record_length_limit: Some(limit),
            },
        )?;
        let mut n = 0;
        while r.next_raw()?.is_some() {
            n += 1;
        }
        Ok::<_, ReadError>(n)
    };
    assert_eq!(read(1 << 24).unwrap(), w.raw.len());
    // The chunk (decompressed: at least its compressed length) is longer than 600
    // bytes; the run metadata record is shorter than the longest record.
    assert!(longest > 2000);
    let e = read(longest / 2).unwrap_err();
    assert!(
        matches!(e, ReadError::Corrupt { .. } | ReadError::NotCarom { .. }),
        "{e:?}"
    );
}
