//! Writing a carom log: an MCAP file with the channels of [`crate::schema`].
//!
//! [`LogWriter`] receives plain engine output (collisions, states, checkpoints) and
//! knows nothing about how the engine works. Collisions are gathered into one reused
//! [`CollisionBatch`] and written as one message per `batch_size` collisions, so the
//! per-collision cost is a few pushes onto vectors; encoding and compression run once
//! per batch.
//!
//! Crash safety: MCAP chunks are written straight to the file; [`LogWriter::flush`]
//! closes the current chunk and hands every byte to the operating system, after which
//! a reader sees everything written so far even if the process is killed. The writer
//! flushes by itself every `flush_seconds` of wall time (checked in
//! [`LogWriter::maybe_flush`] and whenever a batch is written) and after every
//! checkpoint.
//!
//! Ordering: before any snapshot, thermo or checkpoint message the pending collision
//! batch is written, so the file holds messages of all channels in time order.

use crate::cdr::CdrWriter;
use crate::checkpoint_codec::{DriverState, LogCheckpoint, CHECKPOINT_MSG};
use crate::options::{Compression, LogOptions};
use crate::schema::*;
use carom_events::{Checkpoint, PairCollision, State, WallCollision};
use mcap::records::{MessageHeader, Metadata};
use std::collections::BTreeMap;
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use thiserror::Error;

/// Index of `/collisions` in per-channel arrays.
pub const CH_COLLISIONS: usize = 0;
/// Index of `/snapshot` in per-channel arrays.
pub const CH_SNAPSHOT: usize = 1;
/// Index of `/thermo` in per-channel arrays.
pub const CH_THERMO: usize = 2;
/// Index of `/checkpoint` in per-channel arrays.
pub const CH_CHECKPOINT: usize = 3;
/// Topics in per-channel-array order.
pub const TOPICS: [&str; 4] = [
    TOPIC_COLLISIONS,
    TOPIC_SNAPSHOT,
    TOPIC_THERMO,
    TOPIC_CHECKPOINT,
];

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
    /// A call came after [`LogWriter::finish`].
    #[error("log {0} is already finished")]
    Finished(PathBuf),
}

/// How a log is written (the writer's view of [`LogOptions`] plus tuning knobs).
#[derive(Debug, Clone, PartialEq)]
pub struct WriterOptions {
    /// Log collisions at all.
    pub collisions: bool,
    /// Log the collisions whose ordinal is a multiple of this (≥ 1).
    pub collision_every: u64,
    /// Chunk compression.
    pub compression: Compression,
    /// Compression level (zstd: 1–22, lz4: 0–12); 0 = the library default.
    pub compression_level: u32,
    /// Worker threads for zstd (0 = compress on the calling thread).
    pub compression_threads: u32,
    /// Target uncompressed chunk size (bytes).
    pub chunk_size: u64,
    /// Collisions per `/collisions` message.
    pub batch_size: usize,
    /// Wall-clock time between forced flushes.
    pub flush_every: Duration,
}

/// zstd level used by default: level 1 compresses carom's collision data almost as
/// well as the library default (3) at about twice the speed (see
/// `docs/log-format.md`, "Throughput").
pub const DEFAULT_ZSTD_LEVEL: u32 = 1;
/// Collisions per `/collisions` message by default.
pub const DEFAULT_BATCH_SIZE: usize = 4096;
/// Target uncompressed chunk size by default (bytes).
pub const DEFAULT_CHUNK_SIZE: u64 = 4 << 20;

impl WriterOptions {
    /// The writer options for the user's log options (defaults for the rest).
    pub fn from_log_options(o: &LogOptions) -> Self {
        WriterOptions {
            collisions: o.collisions,
            collision_every: o.collision_every.max(1),
            compression: o.compression,
            compression_level: match o.compression {
                Compression::Zstd => DEFAULT_ZSTD_LEVEL,
                _ => 0,
            },
            compression_threads: 1,
            chunk_size: DEFAULT_CHUNK_SIZE,
            batch_size: DEFAULT_BATCH_SIZE,
            flush_every: Duration::from_secs_f64(if o.flush_seconds.is_finite() {
                o.flush_seconds.clamp(0.0, 1e9)
            } else {
                1e9
            }),
        }
    }
}

impl Default for WriterOptions {
    fn default() -> Self {
        Self::from_log_options(&LogOptions::default())
    }
}

/// Counters of what a writer has written.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WriterStats {
    /// Collisions seen (logged or not) since the writer started, plus the starting ordinal.
    pub next_ordinal: u64,
    /// Collisions written to `/collisions` over the run (including before a resume).
    pub logged_collisions: u64,
    /// Messages written per channel by this writer (see [`TOPICS`]).
    pub messages: [u64; 4],
    /// Uncompressed bytes of message payloads per channel by this writer.
    pub payload_bytes: [u64; 4],
    /// Forced flushes so far.
    pub flushes: u64,
}

/// Writes a carom log. Create with [`LogWriter::create`], feed it with the
/// `observe_*` and `write_*` methods, end with [`LogWriter::finish`].
pub struct LogWriter {
    path: PathBuf,
    mcap: Option<mcap::Writer<BufWriter<File>>>,
    channel_ids: [u16; 4],
    next_sequence: [u32; 4],
    opts: WriterOptions,
    batch: CollisionBatch,
    cdr: CdrWriter,
    last_flush: Instant,
    stats: WriterStats,
}

impl std::fmt::Debug for LogWriter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LogWriter")
            .field("path", &self.path)
            .field("stats", &self.stats)
            .finish_non_exhaustive()
    }
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

impl LogWriter {
    /// Create `path` (truncating it), write the `carom.run` metadata record and
    /// register the four channels.
    pub fn create(
        path: &Path,
        opts: WriterOptions,
        run_metadata: &BTreeMap<String, String>,
        position: WriterPosition,
    ) -> Result<LogWriter, WriteError> {
        let file = File::create(path).map_err(|source| WriteError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        let compression = match opts.compression {
            Compression::Zstd => Some(mcap::Compression::Zstd),
            Compression::Lz4 => Some(mcap::Compression::Lz4),
            Compression::None => None,
        };
        let mcap_err = |source| WriteError::Mcap {
            path: path.to_path_buf(),
            source,
        };
        let mut mcap = mcap::WriteOptions::new()
            .compression(compression)
            .compression_level(opts.compression_level)
            .compression_threads(opts.compression_threads)
            .chunk_size(Some(opts.chunk_size))
            .library(format!("carom-io {}", env!("CARGO_PKG_VERSION")))
            .create(BufWriter::with_capacity(1 << 20, file))
            .map_err(mcap_err)?;
        mcap.write_metadata(&Metadata {
            name: METADATA_RUN.into(),
            metadata: run_metadata.clone(),
        })
        .map_err(mcap_err)?;
        let schemas: [(&str, &str, &str); 4] = [
            (
                SCHEMA_COLLISION_BATCH,
                SCHEMA_ENCODING_ROS2MSG,
                COLLISION_BATCH_MSG,
            ),
            (SCHEMA_SNAPSHOT, SCHEMA_ENCODING_ROS2MSG, SNAPSHOT_MSG),
            (
                SCHEMA_THERMO,
                SCHEMA_ENCODING_JSONSCHEMA,
                THERMO_JSON_SCHEMA,
            ),
            (SCHEMA_CHECKPOINT, SCHEMA_ENCODING_ROS2MSG, CHECKPOINT_MSG),
        ];
        let mut channel_ids = [0u16; 4];
        for (k, (name, enc, text)) in schemas.iter().enumerate() {
            let sid = mcap
                .add_schema(name, enc, text.as_bytes())
                .map_err(mcap_err)?;
            let menc = if k == CH_THERMO {
                MESSAGE_ENCODING_JSON
            } else {
                MESSAGE_ENCODING_CDR
            };
            channel_ids[k] = mcap
                .add_channel(sid, TOPICS[k], menc, &BTreeMap::new())
                .map_err(mcap_err)?;
        }
        let mut batch = CollisionBatch::with_capacity(opts.batch_size.max(1));
        batch.stride = opts.collision_every.max(1);
        let mut cdr = CdrWriter::new();
        cdr.reserve(batch.encoded_len() + opts.batch_size * 113);
        Ok(LogWriter {
            path: path.to_path_buf(),
            mcap: Some(mcap),
            channel_ids,
            next_sequence: position.next_sequence,
            opts,
            batch,
            cdr,
            last_flush: Instant::now(),
            stats: WriterStats {
                next_ordinal: position.next_ordinal,
                logged_collisions: position.logged_collisions,
                ..WriterStats::default()
            },
        })
    }

    /// The log file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// What has been written so far.
    pub fn stats(&self) -> WriterStats {
        self.stats
    }

    /// The options in force.
    pub fn options(&self) -> &WriterOptions {
        &self.opts
    }

    fn mcap_err(&self, source: mcap::McapError) -> WriteError {
        WriteError::Mcap {
            path: self.path.clone(),
            source,
        }
    }

    /// Write one message of channel `ch` from `self.cdr` or `data`.
    fn write_message(
        &mut self,
        ch: usize,
        log_time: u64,
        publish_time: u64,
        json: Option<&[u8]>,
    ) -> Result<(), WriteError> {
        let header = MessageHeader {
            channel_id: self.channel_ids[ch],
            sequence: self.next_sequence[ch],
            log_time,
            publish_time,
        };
        let data = json.unwrap_or(self.cdr.bytes());
        let len = data.len() as u64;
        let Some(w) = self.mcap.as_mut() else {
            return Err(WriteError::Finished(self.path.clone()));
        };
        let r = w.write_to_known_channel(&header, data);
        r.map_err(|e| self.mcap_err(e))?;
        self.next_sequence[ch] = self.next_sequence[ch].wrapping_add(1);
        self.stats.messages[ch] += 1;
        self.stats.payload_bytes[ch] += len;
        Ok(())
    }

    /// Account for one pair collision (logged if it is the k-th).
    #[inline]
    pub fn observe_pair(&mut self, c: &PairCollision) -> Result<(), WriteError> {
        let ordinal = self.stats.next_ordinal;
        self.stats.next_ordinal += 1;
        if self.opts.collisions && ordinal % self.opts.collision_every == 0 {
            if self.batch.is_empty() {
                self.batch.first_ordinal = ordinal;
            }
            self.batch.push_pair(c);
            if self.batch.len() >= self.opts.batch_size {
                self.write_batch()?;
                self.maybe_flush()?;
            }
        }
        Ok(())
    }

    /// Account for one wall collision (logged if it is the k-th).
    #[inline]
    pub fn observe_wall(&mut self, c: &WallCollision) -> Result<(), WriteError> {
        let ordinal = self.stats.next_ordinal;
        self.stats.next_ordinal += 1;
        if self.opts.collisions && ordinal % self.opts.collision_every == 0 {
            if self.batch.is_empty() {
                self.batch.first_ordinal = ordinal;
            }
            self.batch.push_wall(c);
            if self.batch.len() >= self.opts.batch_size {
                self.write_batch()?;
                self.maybe_flush()?;
            }
        }
        Ok(())
    }

    /// Write the pending collisions (if any) as one `/collisions` message.
    pub fn write_batch(&mut self) -> Result<(), WriteError> {
        if self.batch.is_empty() {
            return Ok(());
        }
        self.batch.encode(&mut self.cdr);
        let t0 = log_time_ns(self.batch.time[0]);
        let t1 = log_time_ns(self.batch.time[self.batch.len() - 1]);
        self.write_message(CH_COLLISIONS, t0, t1, None)?;
        self.stats.logged_collisions += self.batch.len() as u64;
        self.batch.clear();
        Ok(())
    }

    /// Write a `/snapshot` of `state` (after the pending collisions).
    pub fn write_snapshot(&mut self, state: &State) -> Result<(), WriteError> {
        self.write_batch()?;
        Snapshot::from_state(state).encode(&mut self.cdr);
        let t = log_time_ns(state.time);
        self.write_message(CH_SNAPSHOT, t, t, None)
    }

    /// Write a `/thermo` record (after the pending collisions).
    pub fn write_thermo(&mut self, thermo: &Thermo) -> Result<(), WriteError> {
        self.write_batch()?;
        let json = serde_json::to_vec(thermo).map_err(|source| WriteError::Json {
            path: self.path.clone(),
            source,
        })?;
        let t = log_time_ns(thermo.time);
        self.write_message(CH_THERMO, t, t, Some(&json))
    }

    /// Write a `/checkpoint` of `engine` (after the pending collisions) and flush the
    /// file. The driver state stored with it carries this writer's counters, so a run
    /// resumed from it continues the log exactly.
    pub fn write_checkpoint(
        &mut self,
        engine: Checkpoint,
        run_start_time: f64,
    ) -> Result<(), WriteError> {
        self.write_batch()?;
        let mut next_sequence = self.next_sequence;
        next_sequence[CH_CHECKPOINT] = next_sequence[CH_CHECKPOINT].wrapping_add(1);
        let t = log_time_ns(engine.now);
        let lc = LogCheckpoint {
            driver: DriverState {
                run_start_time,
                logged_collisions: self.stats.logged_collisions,
                next_sequence,
            },
            engine,
        };
        lc.encode(&mut self.cdr);
        self.write_message(CH_CHECKPOINT, t, t, None)?;
        self.flush()
    }

    /// Write a metadata record (after the pending collisions; closes the chunk).
    pub fn write_metadata(
        &mut self,
        name: &str,
        metadata: &BTreeMap<String, String>,
    ) -> Result<(), WriteError> {
        self.write_batch()?;
        let Some(w) = self.mcap.as_mut() else {
            return Err(WriteError::Finished(self.path.clone()));
        };
        let r = w.write_metadata(&Metadata {
            name: name.into(),
            metadata: metadata.clone(),
        });
        r.map_err(|e| self.mcap_err(e))
    }

    /// Copy a message from another carom log verbatim (same channel, sequence,
    /// times and bytes). Used by resume to carry a log's prefix into a new file.
    pub fn copy_message(
        &mut self,
        ch: usize,
        sequence: u32,
        log_time: u64,
        publish_time: u64,
        data: &[u8],
    ) -> Result<(), WriteError> {
        self.write_batch()?;
        let header = MessageHeader {
            channel_id: self.channel_ids[ch],
            sequence,
            log_time,
            publish_time,
        };
        let Some(w) = self.mcap.as_mut() else {
            return Err(WriteError::Finished(self.path.clone()));
        };
        let r = w.write_to_known_channel(&header, data);
        r.map_err(|e| self.mcap_err(e))?;
        self.stats.messages[ch] += 1;
        self.stats.payload_bytes[ch] += data.len() as u64;
        Ok(())
    }

    /// Flush if `flush_every` of wall time has passed since the last flush.
    #[inline]
    pub fn maybe_flush(&mut self) -> Result<(), WriteError> {
        if self.last_flush.elapsed() >= self.opts.flush_every {
            self.flush()?;
        }
        Ok(())
    }

    /// Close the current chunk and hand everything written so far to the operating
    /// system (the pending collision batch is written first). After this a killed
    /// process leaves a file readable up to here.
    pub fn flush(&mut self) -> Result<(), WriteError> {
        self.write_batch()?;
        let Some(w) = self.mcap.as_mut() else {
            return Err(WriteError::Finished(self.path.clone()));
        };
        let r = w.flush();
        r.map_err(|e| self.mcap_err(e))?;
        self.last_flush = Instant::now();
        self.stats.flushes += 1;
        Ok(())
    }

    /// Write the pending batch, the `carom.summary` metadata record and the MCAP
    /// summary section, and close the file. Returns the file size in bytes.
    pub fn finish(&mut self, summary: &BTreeMap<String, String>) -> Result<u64, WriteError> {
        self.write_metadata(METADATA_SUMMARY, summary)?;
        let Some(mut w) = self.mcap.take() else {
            return Err(WriteError::Finished(self.path.clone()));
        };
        w.finish().map_err(|e| self.mcap_err(e))?;
        let mut buf = w.into_inner();
        use std::io::Write;
        buf.flush().map_err(|source| WriteError::Io {
            path: self.path.clone(),
            source,
        })?;
        let file = buf.into_inner().map_err(|e| WriteError::Io {
            path: self.path.clone(),
            source: e.into_error(),
        })?;
        let len = file
            .metadata()
            .map_err(|source| WriteError::Io {
                path: self.path.clone(),
                source,
            })?
            .len();
        Ok(len)
    }
}
