//! Repairing a log cut short (a killed run) without simulating again.
//!
//! [`repair`] reads a log up to its last complete record, as every reader does,
//! and writes a **new**, complete and indexed log (MCAP summary section with
//! statistics and chunk, message and metadata indexes, footer) that holds the
//! `carom.run` record and every readable message, copied byte for byte (same
//! channel, sequence number, times and bytes). A cut log has no `carom.summary`
//! record and the repaired one has none either: the run did not end. A complete
//! input is copied whole, its `carom.summary` included. A log damaged inside its
//! chunks (a flipped bit) is read around the damage: every chunk whose CRC holds
//! is copied and the lost ones are named. Like `mcap recover`; to continue the run
//! instead, use `resume`.

use std::io::{Read, Seek};
use std::path::{Path, PathBuf};

use carom_log::{
    salvage, LogEnd, LogReader, LogWriter, LostPart, ReadError, WriterOptions, WriterPosition,
    CH_CHECKPOINT, CH_COLLISIONS, CH_SNAPSHOT,
};

use super::RunError;

/// What [`repair`] wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct Repaired {
    /// The new log.
    pub out: PathBuf,
    /// Messages copied.
    pub messages: u64,
    /// Its size in bytes.
    pub bytes: u64,
    /// How the input ended (`Complete`, `Truncated` with where it was cut,
    /// `Damaged` after its last chunk, or `Failed` when it was read around
    /// damage: chunks lost, or a damaged start or record framing).
    pub input_end: LogEnd,
    /// The parts of the input that could not be read (damaged chunks), empty
    /// unless the input was damaged before its end.
    pub lost: Vec<LostPart>,
    /// Compact `/collisions` batches left out after a lost part, up to the next
    /// snapshot or checkpoint (they replay velocities from the last one, which a
    /// gap would make wrong).
    pub dropped_batches: u64,
}

/// Write the readable part of the log `input` as a complete log `out` (which must
/// be another file). The new log is written beside `out` and renamed over it only
/// once it is finished, so a failed repair leaves `out` as it was. A log damaged
/// inside its chunks is read around the damage ([`carom_log::salvage`]): every
/// chunk whose CRC holds is copied, and [`Repaired::lost`] names the others.
pub fn repair(input: &Path, out: &Path) -> Result<Repaired, RunError> {
    let mut name = out.file_name().unwrap_or_default().to_os_string();
    name.push(".repair-tmp");
    let tmp = out.with_file_name(name);
    // Read around the damage: the input's reading failed, whatever the salvaged
    // reader's own end says.
    let around = |s: carom_log::Salvaged| {
        copy(s.reader, &tmp, s.lost).map(|r| Repaired {
            input_end: LogEnd::Failed,
            ..r
        })
    };
    let result = match LogReader::open(input) {
        Ok(reader) => match copy(reader, &tmp, Vec::new()) {
            Err(RunError::Read(ReadError::Corrupt { .. })) => around(salvage(input)?),
            other => other,
        },
        // A damaged start (the magic, the header record): what follows may hold.
        // A file salvage cannot read either keeps its first error.
        Err(first @ ReadError::NotCarom { .. }) => match salvage(input) {
            Ok(s) => around(s),
            Err(_) => Err(first.into()),
        },
        Err(e) => Err(e.into()),
    };
    match result {
        Ok(mut r) => {
            std::fs::rename(&tmp, out).map_err(|source| {
                let _ = std::fs::remove_file(&tmp);
                carom_log::WriteError::Io {
                    path: out.to_path_buf(),
                    source,
                }
            })?;
            r.out = out.to_path_buf();
            Ok(r)
        }
        Err(e) => {
            let _ = std::fs::remove_file(&tmp);
            Err(e)
        }
    }
}

/// Copy every message `reader` reads into a new log `out`.
fn copy<R: Read + Seek>(
    mut reader: LogReader<R>,
    out: &Path,
    lost: Vec<LostPart>,
) -> Result<Repaired, RunError> {
    let run_map = reader.run_map().clone();
    let mut writer = LogWriter::create(
        out,
        WriterOptions::from_log_options(&reader.run().log),
        &run_map,
        WriterPosition::default(),
    )?;
    let (mut messages, mut dropped_batches) = (0u64, 0u64);
    let mut next_collisions: Option<u32> = None;
    let mut gap = false;
    let compact_log = reader.run().log.collision_record() == carom_log::CollisionDetail::Compact;
    while let Some(m) = reader.next_raw()? {
        if m.channel == CH_SNAPSHOT || m.channel == CH_CHECKPOINT {
            gap = false;
        }
        if m.channel == CH_COLLISIONS {
            gap |= next_collisions.is_some_and(|s| s != m.sequence);
            next_collisions = Some(m.sequence.wrapping_add(1));
        }
        let compact = m.channel == CH_COLLISIONS && compact_log;
        if gap && compact {
            dropped_batches += 1;
            continue;
        }
        writer.copy_message(m.channel, m.sequence, m.log_time, m.publish_time, m.data)?;
        messages += 1;
        writer.maybe_flush()?;
    }
    let bytes = match reader.summary()? {
        Some(summary) => writer.finish(&summary.to_map())?,
        None => writer.close()?,
    };
    Ok(Repaired {
        out: out.to_path_buf(),
        messages,
        bytes,
        input_end: reader.end().clone(),
        lost,
        dropped_batches,
    })
}
