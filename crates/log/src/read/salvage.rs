//! Salvaging a damaged log: every chunk whose CRC holds, around the ones that do not.
//!
//! A bit flipped inside a chunk stops the MCAP reader there: the chunk's CRC or its
//! decompression fails, or, when the flip hits a length, the framing of every later
//! record. [`salvage`] walks the file's top-level records itself, checks each
//! chunk on its own (a fresh MCAP reader over that one record: CRC, decompression,
//! the records inside) and, after a bad record, looks byte by byte for the next
//! chunk that holds (a CRC-32 match is what marks it). The records kept read as a
//! log ([`LogReader`] over them, with the channel definitions of the index put
//! right after `carom.run`, in case the chunk that defined them was lost); what was
//! lost is listed by byte range. `carom repair` uses it. It holds the file in
//! memory: it is for damaged logs only (repair reads intact and cut logs by
//! streaming).

use super::{parse_record, record_length_limit, LogReader, ReadError, ReadOptions};
use crate::format::{METADATA_RUN, METADATA_SUMMARY};
use mcap::records::{op, Record};
use mcap::sans_io::{LinearReadEvent, LinearReader, LinearReaderOptions};
use std::io::Cursor;
use std::panic::AssertUnwindSafe;
use std::path::Path;

/// A part of a damaged log that [`salvage`] could not read.
#[derive(Debug, Clone, PartialEq)]
pub struct LostPart {
    /// Its first byte.
    pub offset: u64,
    /// Its length (bytes).
    pub length: u64,
    /// What it was, as far as its first record's header says (a chunk with the
    /// times of its messages, or a record of another kind).
    pub what: String,
}

/// What [`salvage`] found: a reader over everything readable, and what was lost.
pub struct Salvaged {
    /// A reader of the kept records (it ends as a log cut short would).
    pub reader: LogReader<Cursor<Vec<u8>>>,
    /// The unreadable parts, in file order.
    pub lost: Vec<LostPart>,
    /// Chunks kept (each one's CRC holds).
    pub chunks_kept: u64,
}

/// The header of a top-level record at `pos`: opcode and the end of the record,
/// if it fits in `bytes` and under `limit`.
fn header_at(bytes: &[u8], pos: usize, limit: usize) -> Option<(u8, usize)> {
    let head = bytes.get(pos..pos.checked_add(9)?)?;
    let len = u64::from_le_bytes(head[1..9].try_into().ok()?);
    let len = usize::try_from(len).ok().filter(|&l| l <= limit)?;
    let end = pos.checked_add(9)?.checked_add(len)?;
    (end <= bytes.len()).then_some((head[0], end))
}

/// Whether the chunk record `record` (opcode and length included) reads whole:
/// its CRC holds and every record inside parses.
fn chunk_holds(record: &[u8], limit: usize) -> bool {
    let check = || {
        let mut r = LinearReader::new_with_options(
            LinearReaderOptions::default()
                .with_skip_start_magic(true)
                .with_skip_end_magic(true)
                .with_prevalidate_chunk_crcs(true)
                .with_record_length_limit(limit),
        );
        let mut fed = 0;
        loop {
            match r.next_event() {
                None => return true,
                Some(Err(_)) => return false,
                Some(Ok(LinearReadEvent::ReadRequest(n))) => {
                    let n = n.min(record.len() - fed);
                    r.insert(n).copy_from_slice(&record[fed..fed + n]);
                    r.notify_read(n);
                    fed += n;
                }
                Some(Ok(LinearReadEvent::Record { data, opcode })) => {
                    if parse_record(opcode, data).is_err() {
                        return false;
                    }
                }
            }
        }
    };
    std::panic::catch_unwind(AssertUnwindSafe(check)).unwrap_or(false)
}

/// A quick look at a chunk's header (before the costly check): the compression
/// is one MCAP names and the compressed size fits in the record.
fn plausible_chunk(bytes: &[u8], pos: usize, end: usize) -> bool {
    let body = &bytes[pos + 9..end];
    if body.len() < 40 {
        return false;
    }
    let name_len = u32::from_le_bytes(body[28..32].try_into().unwrap()) as usize;
    let Some(name) = body.get(32..32 + name_len) else {
        return false;
    };
    let Some(size) = body.get(32 + name_len..40 + name_len) else {
        return false;
    };
    let size = u64::from_le_bytes(size.try_into().unwrap());
    matches!(name, b"" | b"zstd" | b"lz4") && size <= (body.len() - 40 - name_len) as u64
}

/// Whether the record at `pos` (ending at `end`) is whole: a chunk whose CRC
/// holds, or another record that parses.
fn record_holds(bytes: &[u8], pos: usize, op: u8, end: usize, limit: usize) -> bool {
    match op {
        op::CHUNK => plausible_chunk(bytes, pos, end) && chunk_holds(&bytes[pos..end], limit),
        op::HEADER..=op::DATA_END => parse_record(op, &bytes[pos + 9..end]).is_ok(),
        _ => false,
    }
}

/// Whether the record at `pos` can start again after damage: a chunk that holds,
/// or one of carom's metadata records (`carom.run` after a damaged header).
fn resumes_at(bytes: &[u8], pos: usize, limit: usize) -> Option<(u8, usize)> {
    let (op, end) = header_at(bytes, pos, limit)?;
    let ok = match op {
        op::CHUNK => plausible_chunk(bytes, pos, end) && chunk_holds(&bytes[pos..end], limit),
        op::METADATA => matches!(
            parse_record(op, &bytes[pos + 9..end]),
            Ok(Record::Metadata(m)) if m.name == METADATA_SUMMARY || m.name == METADATA_RUN
        ),
        _ => false,
    };
    ok.then_some((op, end))
}

/// What the damaged part starting at `pos` was.
fn describe(bytes: &[u8], pos: usize) -> String {
    if bytes.get(pos) == Some(&op::CHUNK) {
        if let Some(t) = bytes.get(pos + 9..pos + 25) {
            let ns = |b: &[u8]| u64::from_le_bytes(b.try_into().unwrap()) as f64 * 1e-9;
            return format!(
                "a chunk of messages from t ≈ {} to {} (log times)",
                ns(&t[..8]),
                ns(&t[8..])
            );
        }
    }
    format!(
        "a record of opcode {:#04x}",
        bytes.get(pos).copied().unwrap_or(0)
    )
}

/// Read the log `path` around its damage: every record of the data section that
/// holds (each chunk checked by its CRC) is kept, each unreadable stretch listed.
pub fn salvage(path: &Path) -> Result<Salvaged, ReadError> {
    let label = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|source| ReadError::Io {
        file: label.clone(),
        source,
    })?;
    let limit = record_length_limit(bytes.len() as u64);
    let mut kept: Vec<(usize, usize)> = Vec::new();
    let mut definitions: Vec<(usize, usize)> = Vec::new();
    let mut lost = Vec::new();
    let mut chunks_kept = 0;
    let mut bad_from: Option<usize> = None;
    let mut in_summary = false;
    let mut pos = mcap::MAGIC.len().min(bytes.len());
    while pos < bytes.len() {
        let found = match bad_from {
            None => header_at(&bytes, pos, limit)
                .filter(|&(op, end)| record_holds(&bytes, pos, op, end, limit)),
            Some(_) => resumes_at(&bytes, pos, limit),
        };
        let Some((op, end)) = found else {
            bad_from.get_or_insert(pos);
            pos += 1;
            continue;
        };
        if let Some(from) = bad_from.take() {
            lost.push(LostPart {
                offset: from as u64,
                length: (pos - from) as u64,
                what: describe(&bytes, from),
            });
        }
        match op {
            op::FOOTER => break,
            op::DATA_END => in_summary = true,
            op::SCHEMA | op::CHANNEL if in_summary => definitions.push((pos, end)),
            _ if in_summary => {}
            _ => {
                chunks_kept += u64::from(op == op::CHUNK);
                kept.push((pos, end));
            }
        }
        pos = end;
    }
    if let Some(from) = bad_from {
        // Damage up to the end of the file: what follows the last good record.
        if !in_summary {
            lost.push(LostPart {
                offset: from as u64,
                length: (bytes.len() - from) as u64,
                what: describe(&bytes, from),
            });
        }
    }
    let mut out = mcap::MAGIC.to_vec();
    let mut defined = false;
    for &(a, b) in &kept {
        out.extend_from_slice(&bytes[a..b]);
        if !defined && bytes[a] == op::METADATA {
            // Right after `carom.run`: the channels, should their chunk be lost.
            for &(c, d) in &definitions {
                out.extend_from_slice(&bytes[c..d]);
            }
            defined = true;
        }
    }
    let reader = LogReader::new(Cursor::new(out), label, ReadOptions::default())?;
    Ok(Salvaged {
        reader,
        lost,
        chunks_kept,
    })
}
