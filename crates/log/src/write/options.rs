//! How a log is written ([`WriterOptions`]), where a writer starts counting
//! ([`WriterPosition`]), what it has sent ([`WriterStats`]) and how writing fails
//! ([`WriteError`]).

use crate::format::N_CHANNELS;
use crate::options::{CollisionDetail, Compression, LogOptions};
use std::path::{Path, PathBuf};
use std::time::Duration;
use thiserror::Error;

/// A failure while writing a log. Each names the file.
#[derive(Debug, Error)]
pub enum WriteError {
    /// The file could not be created or written.
    #[error("cannot write log {path}: {source}")]
    Io {
        /// The log file.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// The MCAP library reported an error.
    #[error("cannot write log {path}: {source}")]
    Mcap {
        /// The log file.
        path: PathBuf,
        /// The MCAP error.
        source: mcap::McapError,
    },
    /// A thermo record could not be serialised.
    #[error("cannot encode /thermo record for {path}: {source}")]
    Json {
        /// The log file.
        path: PathBuf,
        /// The JSON error.
        source: serde_json::Error,
    },
    /// The writer thread could not be started or died.
    #[error("log writer thread for {path}: {problem}")]
    Thread {
        /// The log file.
        path: PathBuf,
        /// What happened.
        problem: String,
    },
    /// A call came after [`crate::LogWriter::finish`] or after an earlier error.
    #[error("log {0} is already finished or failed")]
    Finished(PathBuf),
}

impl WriteError {
    /// The error for an MCAP failure while writing `path`. The MCAP library wraps
    /// the operating system's errors in a message of its own ("I/O error from
    /// writing, or reading a compression stream") that hides the cause; those are
    /// unwrapped, so that a full disk says "No space left on device".
    pub fn from_mcap(path: &Path, source: mcap::McapError) -> WriteError {
        match source {
            mcap::McapError::Io(source) => WriteError::Io {
                path: path.to_path_buf(),
                source,
            },
            source => WriteError::Mcap {
                path: path.to_path_buf(),
                source,
            },
        }
    }
}

/// How a log is written (the writer's view of [`LogOptions`] plus tuning knobs).
#[derive(Debug, Clone, PartialEq)]
pub struct WriterOptions {
    /// Log collisions at all.
    pub collisions: bool,
    /// Log the collisions whose ordinal is a multiple of this (≥ 1).
    pub collision_every: u64,
    /// The record `/collisions` holds ([`LogOptions::collision_record`]): compact
    /// only with `collision_every` = 1.
    pub collision_detail: CollisionDetail,
    /// Compact records also store the contact normal: set when the run's pair rule
    /// gives impulses off the line of centres (the centre-of-mass rule with R < 1).
    pub collision_normals: bool,
    /// Chunk compression.
    pub compression: Compression,
    /// Compression level: zstd 1 to 22, or negative for zstd's fast levels (−1 to
    /// −7 and below: less CPU, slightly larger files); lz4 0 to 12; 0 means the
    /// library's default.
    pub compression_level: i32,
    /// Target uncompressed chunk size (bytes).
    pub chunk_size: u64,
    /// Collisions per `/collisions` message.
    pub batch_size: usize,
    /// Wall-clock time between forced flushes.
    pub flush_every: Duration,
    /// Encode, compress and write on a separate thread instead of inline (default:
    /// when the machine has more than one core).
    pub background: bool,
}

/// zstd level used by default: −1, zstd's first fast level (collision data
/// hardly compress; the fast level costs least CPU). See docs/performance.md,
/// "Default zstd level −1".
pub const DEFAULT_ZSTD_LEVEL: i32 = -1;
/// Collisions per `/collisions` message by default.
pub const DEFAULT_BATCH_SIZE: usize = 4096;
/// Target uncompressed chunk size by default (bytes).
pub const DEFAULT_CHUNK_SIZE: u64 = 1 << 20;

impl WriterOptions {
    /// The writer options for the user's log options (defaults for the rest).
    pub fn from_log_options(o: &LogOptions) -> Self {
        WriterOptions {
            collisions: o.collisions,
            collision_every: o.collision_every.max(1),
            collision_detail: o.collision_record(),
            collision_normals: false,
            compression: o.compression,
            compression_level: match o.compression {
                Compression::Zstd => DEFAULT_ZSTD_LEVEL,
                _ => 0,
            },
            chunk_size: DEFAULT_CHUNK_SIZE,
            batch_size: DEFAULT_BATCH_SIZE,
            flush_every: Duration::from_secs_f64(if o.flush_seconds.is_finite() {
                o.flush_seconds.clamp(0.0, 1e9)
            } else {
                1e9
            }),
            background: std::thread::available_parallelism().is_ok_and(|n| n.get() > 1),
        }
    }
}

impl WriterOptions {
    /// Whether compact records of a run with pair rule `rule` must store the
    /// contact normal (its impulse is not along the line of centres).
    pub fn needs_normals(rule: carom_core::Restitution) -> bool {
        matches!(rule, carom_core::Restitution::CentreOfMass(r) if r != 1.0)
    }
}

impl Default for WriterOptions {
    fn default() -> Self {
        Self::from_log_options(&LogOptions::default())
    }
}

/// Counters of what a writer has been given.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WriterStats {
    /// Ordinal of the next collision (collisions seen, logged or not, plus the
    /// starting ordinal).
    pub next_ordinal: u64,
    /// Collisions sent to `/collisions` over the run (including before a resume).
    pub logged_collisions: u64,
    /// Messages sent per channel by this writer (see [`crate::TOPICS`]).
    pub messages: [u64; N_CHANNELS],
    /// Encoded size of the largest snapshot, thermo or checkpoint message sent so
    /// far (bytes, before compression).
    pub largest_message: u64,
}

/// Where a writer starts counting (a fresh run starts at zero; a resumed run at the
/// checkpoint's counters).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WriterPosition {
    /// Ordinal of the next collision the writer will observe.
    pub next_ordinal: u64,
    /// Collisions already logged.
    pub logged_collisions: u64,
    /// Next sequence number per channel.
    pub next_sequence: [u32; 4],
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mcap_io_errors_show_the_operating_systems_reason() {
        let io = std::io::Error::from(std::io::ErrorKind::StorageFull);
        let text = io.to_string();
        let e = WriteError::from_mcap(Path::new("run.mcap"), mcap::McapError::Io(io));
        assert!(matches!(e, WriteError::Io { .. }), "{e:?}");
        assert_eq!(e.to_string(), format!("cannot write log run.mcap: {text}"));
        // Other MCAP errors keep the library's own message.
        let e = WriteError::from_mcap(Path::new("run.mcap"), mcap::McapError::TooManyChannels);
        assert!(matches!(e, WriteError::Mcap { .. }), "{e:?}");
    }
}
