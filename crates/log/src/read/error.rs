//! How reading a log fails ([`ReadError`]) and how it ended ([`LogEnd`]).

use crate::format::{CdrError, MetadataError};
use thiserror::Error;

/// Why a log could not be read. Each variant names the file.
#[derive(Debug, Error)]
pub enum ReadError {
    /// The file could not be opened or read.
    #[error("cannot read log {file}: {source}")]
    Io {
        /// The file.
        file: String,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// The file is not an MCAP file written by carom (no `carom.run` metadata first).
    #[error("{file} is not a carom log: {problem}")]
    NotCarom {
        /// The file.
        file: String,
        /// What gave it away.
        problem: String,
    },
    /// The `carom.run` or `carom.summary` metadata is malformed.
    #[error("{file}: {source}")]
    Metadata {
        /// The file.
        file: String,
        /// The problem.
        source: MetadataError,
    },
    /// The file ends before its end (a killed run), in strict mode.
    #[error("{file} is truncated after {messages} messages: {detail}")]
    Truncated {
        /// The file.
        file: String,
        /// Messages read before the cut.
        messages: u64,
        /// The MCAP reader's message.
        detail: String,
    },
    /// The file is damaged (bad CRC, malformed record, undecodable compression).
    #[error("{file} is corrupted after {messages} messages: {detail}")]
    Corrupt {
        /// The file.
        file: String,
        /// Messages read before the damage.
        messages: u64,
        /// The MCAP reader's message.
        detail: String,
    },
    /// A carom topic uses an unexpected schema or encoding.
    #[error("{file}: topic {topic} has schema `{found}`, expected `{expected}`")]
    WrongSchema {
        /// The file.
        file: String,
        /// The topic.
        topic: &'static str,
        /// Schema name and encodings found.
        found: String,
        /// Schema name and encodings expected.
        expected: String,
    },
    /// A message could not be decoded.
    #[error(
        "{file}: {topic} message #{sequence} (log time {log_time} ns) cannot be decoded: {source}"
    )]
    Decode {
        /// The file.
        file: String,
        /// The topic.
        topic: &'static str,
        /// The message's sequence number.
        sequence: u32,
        /// The message's log time (ns).
        log_time: u64,
        /// The CDR problem.
        source: CdrError,
    },
    /// A `/thermo` message is not valid JSON for [`crate::Thermo`].
    #[error("{file}: /thermo message #{sequence} is not a valid thermo record: {source}")]
    Json {
        /// The file.
        file: String,
        /// The message's sequence number.
        sequence: u32,
        /// The JSON problem.
        source: serde_json::Error,
    },
    /// The whole file was read and a channel the caller asked for never appeared.
    #[error("{file} has no {topic} channel{hint}")]
    MissingChannel {
        /// The file.
        file: String,
        /// The topic.
        topic: &'static str,
        /// Extra context (empty or starting with "; ").
        hint: String,
    },
    /// The file holds no checkpoint to resume from.
    #[error("{file} has no complete /checkpoint message to resume from")]
    NoCheckpoint {
        /// The file.
        file: String,
    },
}

/// How reading ended.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum LogEnd {
    /// Not at the end yet.
    Reading,
    /// The file ended properly (MCAP footer and end magic).
    Complete,
    /// The file stops early (a killed run): everything before `detail` was read.
    Truncated {
        /// What the MCAP reader found at the cut.
        detail: String,
    },
    /// Every message was read (each chunk's CRC holds, and the end of the data
    /// section was reached: see the module doc of `read`), but something outside
    /// the chunks is damaged: the index (MCAP summary section), the footer or the
    /// end magic, a `carom.summary` record whose checksum fails (its values are
    /// then not used), or, in a log whose metadata carry checksums (format 2.3
    /// on), the framing of records outside the chunks (the data section's CRC).
    /// A warning, not an error: the index only repeats what the chunks hold, and
    /// readers read the chunks in order.
    Damaged {
        /// What is damaged.
        detail: String,
    },
    /// Reading stopped at an error (see the error returned).
    Failed,
}

impl LogEnd {
    /// A warning for the user when the file was cut short.
    pub fn warning(&self) -> Option<String> {
        match self {
            LogEnd::Truncated { detail } => Some(format!(
                "the log is truncated (the run was killed or is still being written); \
                 read everything up to the last flush ({detail})"
            )),
            LogEnd::Damaged { detail } => Some(format!(
                "the log is damaged outside its chunks ({detail}); every message was read from \
                 the chunks in order, each chunk's CRC holding (`carom repair` writes an intact copy)"
            )),
            _ => None,
        }
    }
}
