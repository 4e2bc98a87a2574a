//! [`scan_indexed`]: what [`super::scan`] finds, for a log that was finished
//! properly, from its index and the few chunks holding each channel's first and
//! last message instead of the whole file.

use super::scan::simulated_times;
use super::{record_length_limit, LogEnd, LogInfo, LogReader, RawMessage, ReadError};
use crate::format::N_CHANNELS;
use crate::format::{
    verify, Checksum, SummaryMetadata, Thermo, CH_CHECKPOINT, CH_THERMO, METADATA_SUMMARY, TOPICS,
};
use mcap::records::Record;
use std::collections::HashMap;
use std::fs::File;
use std::io::{Read, Seek, SeekFrom};
use std::path::Path;

/// [`scan`](crate::scan)'s findings for a log that was finished properly, read from its index
/// (the MCAP summary section) and the few chunks that hold each channel's first and
/// last messages, instead of from the whole file: what `carom analyze` needs before
/// its own pass over every message. Message counts come from the index's
/// statistics, logged collisions from the `carom.summary` metadata, and times and
/// thermo counts from the messages themselves, so the result equals [`scan`](crate::scan)'s for
/// an intact file. Nothing else in the file is read or checked: damage elsewhere is
/// found only by a later full read. `Ok(None)` when the file has no usable index (a
/// run cut short, a damaged index or footer, no `carom.summary` record or one
/// whose checksum fails; then use [`scan`](crate::scan), which says what is
/// damaged). An error only when `carom.run` cannot be read, or the file itself.
pub fn scan_indexed(path: &Path) -> Result<Option<LogInfo>, ReadError> {
    use mcap::sans_io::summary_reader::{SummaryReadEvent, SummaryReader, SummaryReaderOptions};

    let label = path.display().to_string();
    let io = |source| ReadError::Io {
        file: label.clone(),
        source,
    };
    let head = LogReader::open(path)?;
    let mut file = File::open(path).map_err(io)?;
    let file_bytes = file.metadata().map_err(io)?.len();
    if !head.has_end_magic || !summary_crc_holds(&mut file, file_bytes).map_err(io)? {
        return Ok(None);
    }
    // Knowing the file's size, the summary reader never asks for more bytes than
    // are left (a damaged length cannot make it allocate gigabytes).
    let mut summary_reader = SummaryReader::new_with_options(
        SummaryReaderOptions::default()
            .with_file_size(file_bytes)
            .with_record_length_limit(record_length_limit(file_bytes)),
    );
    while let Some(event) = summary_reader.next_event() {
        let Ok(event) = event else { return Ok(None) };
        match event {
            SummaryReadEvent::ReadRequest(need) => {
                let n = file.read(summary_reader.insert(need)).map_err(io)?;
                summary_reader.notify_read(n);
            }
            SummaryReadEvent::SeekRequest(to) => {
                summary_reader.notify_seeked(file.seek(to).map_err(io)?);
            }
        }
    }
    let Some(summary) = summary_reader.finish() else {
        return Ok(None);
    };
    let Some(stats) = &summary.stats else {
        return Ok(None);
    };
    // Our channel index of each MCAP channel id.
    let ours: HashMap<u16, usize> = summary
        .channels
        .iter()
        .filter_map(|(&id, c)| TOPICS.iter().position(|&t| t == c.topic).map(|k| (id, k)))
        .collect();
    let mut channels = [false; N_CHANNELS];
    let mut messages = [0u64; N_CHANNELS];
    for (&id, &k) in &ours {
        channels[k] = true;
        messages[k] += stats.channel_message_counts.get(&id).copied().unwrap_or(0);
    }
    // The carom.summary metadata (logged collisions, and the summary itself).
    let Some(index) = summary
        .metadata_indexes
        .iter()
        .find(|m| m.name == METADATA_SUMMARY)
    else {
        return Ok(None);
    };
    // (An index pointing outside the file is damage: left to the full scan, as is
    // any other inconsistency below.)
    if index.length < 9 || index.offset.saturating_add(index.length) > file_bytes {
        return Ok(None);
    }
    let mut record = vec![0u8; index.length as usize];
    file.seek(SeekFrom::Start(index.offset)).map_err(io)?;
    file.read_exact(&mut record).map_err(io)?;
    // A record is its opcode, its length (u64) and its body.
    let Ok(Record::Metadata(m)) = super::parse_record(record[0], &record[9..]) else {
        return Ok(None);
    };
    // A summary whose checksum fails is damage: the full scan says so.
    if matches!(verify(&m.metadata), Checksum::Fails { .. }) {
        return Ok(None);
    }
    let Ok(carom_summary) = SummaryMetadata::from_map(&m.metadata) else {
        return Ok(None);
    };
    // The chunks (in file order) that hold each channel's first and last message.
    let mut chunks = summary.chunk_indexes.clone();
    chunks.sort_by_key(|c| c.chunk_start_offset);
    // A chunk without message indexes holds no messages (only schemas and channels,
    // as when they outgrow the chunk size) or comes from a writer that wrote no
    // indexes; reading it tells which, and only the first kind is left out.
    let mut unindexed = Vec::new();
    chunks.retain(|c| {
        let empty = c.message_index_offsets.is_empty();
        if empty {
            unindexed.push(c.clone());
        }
        !empty
    });
    for c in &unindexed {
        let mut any = false;
        if !each_message(&mut file, c, file_bytes, &io, |_, _| {
            any = true;
            false
        })? || any
        {
            return Ok(None);
        }
    }
    let ours = &ours;
    let holding = |k: usize| {
        move |c: &&mcap::records::ChunkIndex| {
            c.message_index_offsets
                .keys()
                .any(|id| ours.get(id) == Some(&k))
        }
    };
    let mut ends: [Option<(RawOwned, RawOwned)>; N_CHANNELS] = Default::default();
    for (k, end) in ends.iter_mut().enumerate() {
        let (Some(first), Some(last)) = (
            chunks.iter().find(holding(k)),
            chunks.iter().rfind(holding(k)),
        ) else {
            continue;
        };
        let mut pick = |chunk: &mcap::records::ChunkIndex,
                        want_last: bool|
         -> Result<Option<RawOwned>, ReadError> {
            let mut found: Option<RawOwned> = None;
            let read = each_message(&mut file, chunk, file_bytes, &io, |header, data| {
                if ours.get(&header.channel_id) == Some(&k) {
                    found = Some(RawOwned {
                        channel: k,
                        log_time: header.log_time,
                        publish_time: header.publish_time,
                        data: data.to_vec(),
                    });
                    return want_last;
                }
                true
            })?;
            Ok(if read { found } else { None })
        };
        let (Some(a), Some(b)) = (pick(first, false)?, pick(last, true)?) else {
            return Ok(None);
        };
        *end = Some((a, b));
    }
    let mut time_span: [Option<(f64, f64)>; N_CHANNELS] = [None; N_CHANNELS];
    for (span, end) in time_span.iter_mut().zip(&ends) {
        if let Some((a, b)) = end {
            let (t0, _) = simulated_times(&a.raw());
            let (_, t1) = simulated_times(&b.raw());
            *span = Some((t0, t1));
        }
    }
    let last_checkpoint_time = ends[CH_CHECKPOINT]
        .as_ref()
        .map(|(_, b)| simulated_times(&b.raw()).0);
    let thermo_counts = match &ends[CH_THERMO] {
        Some((a, b)) => {
            let count = |m: &RawOwned| {
                Thermo::decode(&m.data)
                    .ok()
                    .map(|t| (t.time, t.pair_collisions, t.wall_collisions))
            };
            match (count(a), count(b)) {
                (Some(x), Some(y)) => Some([x, y]),
                _ => return Ok(None),
            }
        }
        None => None,
    };
    Ok(Some(LogInfo {
        run: head.run.clone(),
        summary: Some(carom_summary.clone()),
        end: LogEnd::Complete,
        channels,
        messages,
        logged_collisions: carom_summary.logged_collisions,
        time_span,
        last_checkpoint_time,
        thermo_counts,
        file_bytes,
    }))
}

/// Whether the index (the MCAP summary section) is intact: the footer is where it
/// belongs and the CRC it stores matches the summary section and the footer's
/// first 16 bytes (MCAP's rule; a CRC of 0 means none was written).
fn summary_crc_holds(file: &mut File, file_bytes: u64) -> std::io::Result<bool> {
    const FOOTER: usize = 1 + 8 + 20; // opcode, length, body
    let Some(footer_start) = file_bytes.checked_sub((8 + FOOTER) as u64) else {
        return Ok(false);
    };
    let mut footer = [0u8; FOOTER];
    file.seek(SeekFrom::Start(footer_start))?;
    file.read_exact(&mut footer)?;
    let word = |a: usize| u64::from_le_bytes(footer[a..a + 8].try_into().unwrap());
    if footer[0] != mcap::records::op::FOOTER || word(1) != 20 {
        return Ok(false);
    }
    let summary_start = word(9);
    let saved = u32::from_le_bytes(footer[25..29].try_into().unwrap());
    if summary_start < 8 || summary_start > footer_start {
        return Ok(false);
    }
    if saved == 0 {
        return Ok(true);
    }
    let mut hasher = crc32fast::Hasher::new();
    file.seek(SeekFrom::Start(summary_start))?;
    let mut rest = footer_start - summary_start;
    let mut buf = vec![0u8; 1 << 16];
    while rest > 0 {
        let n = rest.min(buf.len() as u64) as usize;
        file.read_exact(&mut buf[..n])?;
        hasher.update(&buf[..n]);
        rest -= n as u64;
    }
    hasher.update(&footer[..25]);
    Ok(hasher.finalize() == saved)
}

/// A message copied out of its chunk (see [`scan_indexed`]).
struct RawOwned {
    channel: usize,
    log_time: u64,
    publish_time: u64,
    data: Vec<u8>,
}

impl RawOwned {
    fn raw(&self) -> RawMessage<'_> {
        RawMessage {
            channel: self.channel,
            sequence: 0,
            log_time: self.log_time,
            publish_time: self.publish_time,
            data: &self.data,
        }
    }
}

/// Read the messages of one chunk in file order, handing each to `visit` until it
/// returns false; `Ok(false)` when the chunk cannot be read as its index says.
fn each_message(
    file: &mut File,
    chunk: &mcap::records::ChunkIndex,
    file_bytes: u64,
    io: &impl Fn(std::io::Error) -> ReadError,
    mut visit: impl FnMut(&mcap::records::MessageHeader, &[u8]) -> bool,
) -> Result<bool, ReadError> {
    use mcap::sans_io::indexed_reader::{
        IndexedReadEvent, IndexedReader, IndexedReaderOptions, ReadOrder,
    };
    // The reader needs only the chunk's index: it looks at the summary's channels
    // only to filter by topic, which is not asked for here.
    let one = mcap::Summary {
        chunk_indexes: vec![chunk.clone()],
        ..Default::default()
    };
    let Ok(mut reader) = IndexedReader::new_with_options(
        &one,
        IndexedReaderOptions::new()
            .with_order(ReadOrder::File)
            .with_record_length_limit(record_length_limit(file_bytes)),
    ) else {
        return Ok(false);
    };
    let mut buf = Vec::new();
    while let Some(event) = reader.next_event() {
        let Ok(event) = event else { return Ok(false) };
        match event {
            IndexedReadEvent::ReadChunkRequest { offset, length } => {
                if offset.saturating_add(length as u64) > file_bytes {
                    return Ok(false);
                }
                file.seek(SeekFrom::Start(offset)).map_err(io)?;
                buf.resize(length, 0);
                file.read_exact(&mut buf).map_err(io)?;
                if reader.insert_chunk_record_data(offset, &buf).is_err() {
                    return Ok(false);
                }
            }
            IndexedReadEvent::Message { header, data } => {
                if !visit(&header, data) {
                    break;
                }
            }
        }
    }
    Ok(true)
}
