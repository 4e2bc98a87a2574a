//! `LogReader::read_ahead`: the records read and decompressed on a second thread
//! are the inline reader's, byte for byte, and a cut or damaged file ends or
//! fails at the same message with the same words.

mod log_common;
use log_common::*;

/// Every raw message (channel, sequence, times, bytes) until the end or an
/// error, and how it ended: `Ok(end)` or the error's text.
fn read_all(
    mut r: LogReader<std::io::Cursor<Vec<u8>>>,
) -> (Vec<(usize, u32, u64, u64, Vec<u8>)>, Result<String, String>) {
    let mut out = Vec::new();
    loop {
        match r.next_raw() {
            Ok(Some(m)) => out.push((
                m.channel,
                m.sequence,
                m.log_time,
                m.publish_time,
                m.data.to_vec(),
            )),
            Ok(None) => return (out, Ok(format!("{:?}", r.end()))),
            Err(e) => return (out, Err(e.to_string())),
        }
    }
}

/// Inline and read-ahead readers of `bytes` agree on everything.
fn same(bytes: &[u8], strict: bool, what: &str) -> usize {
    let inline = read_all(reader(bytes.to_vec(), strict).unwrap());
    let ahead = read_all(reader(bytes.to_vec(), strict).unwrap().read_ahead());
    assert_eq!(inline.0.len(), ahead.0.len(), "{what}");
    assert!(inline.0 == ahead.0, "{what}: messages differ");
    assert_eq!(inline.1, ahead.1, "{what}");
    inline.0.len()
}

#[test]
fn a_whole_log_reads_the_same_ahead() {
    for compression in [Compression::None, Compression::Zstd] {
        let w = write_log(
            "ahead-whole",
            Plan {
                compression,
                flush_each: true,
                t_end: 1.0,
                ..Plan::default()
            },
        );
        let n = same(&w.bytes(), true, "whole");
        assert_eq!(n, w.raw.len());
        // The decoding iterators too.
        let events = |r: LogReader<std::io::Cursor<Vec<u8>>>| {
            let mut r = r;
            r.events().map(|e| e.unwrap()).collect::<Vec<_>>()
        };
        let bytes = w.bytes();
        let a = events(reader(bytes.clone(), true).unwrap());
        let b = events(reader(bytes, true).unwrap().read_ahead());
        assert!(!a.is_empty() && a == b);
    }
}

#[test]
fn cut_and_damaged_logs_end_alike_ahead() {
    let w = write_log(
        "ahead-cut",
        Plan {
            compression: Compression::Zstd,
            flush_each: true,
            t_end: 1.0,
            ..Plan::default()
        },
    );
    let bytes = w.bytes();
    let ch = chunks(&bytes);
    assert!(ch.len() >= 4);
    for k in 1..ch.len() - 1 {
        let (start, len) = ch[k];
        let cut = &bytes[..start + len / 2];
        for strict in [false, true] {
            same(cut, strict, &format!("cut in chunk {k}, strict {strict}"));
        }
        let mut bad = bytes.clone();
        bad[start + len - 3] ^= 0x5a;
        let n = same(&bad, false, &format!("damage in chunk {k}"));
        assert!(n < w.raw.len());
    }
}
