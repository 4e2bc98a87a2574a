//! Repairing a log cut short (a killed run) without simulating again.
//!
//! [`repair`] reads a log up to its last complete record, as every reader does,
//! and writes a **new**, complete and indexed log (MCAP summary section with
//! statistics and chunk, message and metadata indexes, footer) that holds the
//! `carom.run` record and every readable message, copied byte for byte (same
//! channel, sequence number, times and bytes). A cut log has no `carom.summary`
//! record and the repaired one has none either: the run did not end. A complete
//! input is copied whole, its `carom.summary` included. Like `mcap recover`; to
//! continue the run instead, use `resume`.

use std::path::{Path, PathBuf};

use carom_io::{LogEnd, LogReader, LogWriter, WriterOptions, WriterPosition};

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
    /// How the input ended (`Complete`, or `Truncated` with where it was cut).
    pub input_end: LogEnd,
}

/// Write the readable part of the log `input` as a complete log `out` (which must
/// be another file; it is created or truncated).
pub fn repair(input: &Path, out: &Path) -> Result<Repaired, RunError> {
    let mut reader = LogReader::open(input)?;
    let run_map = reader.run_map().clone();
    let mut writer = LogWriter::create(
        out,
        WriterOptions::from_log_options(&reader.run().log),
        &run_map,
        WriterPosition::default(),
    )?;
    let mut messages = 0u64;
    while let Some(m) = reader.next_raw()? {
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
    })
}
